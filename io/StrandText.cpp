#include "io/StrandText.h"

#include "io/AtomicFile.h"
#include "io/RegularFile.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace wisp::io {

Result<void> writeStrandText(const std::string& path, const HairCurves& curves)
{
    return writeFileAtomically(path, [&](std::ostream& out) {
        out << "wisp-strands 1\n";
        out << "strands " << curves.strandCount() << " points " << curves.pointCount() << "\n";
        char number[64]; // three of " -1.23456789e+38" (16 characters each) and the NUL
        std::string line;
        for (std::size_t s = 0; s < curves.strandCount(); ++s) {
            line = std::to_string(curves.pointsIn(s));
            for (const glm::vec3& p : curves.strand(s)) {
                // %.9g round-trips a float exactly.
                std::snprintf(number, sizeof number, " %.9g %.9g %.9g", p.x, p.y, p.z);
                line += number;
            }
            line += '\n';
            out << line;
        }
    });
}

Result<HairCurves> readStrandText(const std::string& path)
{
    Result<std::string> file = readRegularFile(path, { kMaxStrandTextBytes, "wisp-strands", false });
    if (!file)
        return file.error();
    // The size of the text, taken before the stream: a stream at its end (a header with no newline
    // after it) answers tellg() with -1, which read as the largest size let any count through
    // (found by fuzz/fuzz_hair in CI).
    const std::size_t size = file.value().size();
    std::istringstream in(std::move(file).value());
    std::string line;
    std::size_t lineNumber = 0;
    auto nextLine = [&]() -> bool {
        while (std::getline(in, line)) {
            ++lineNumber;
            if (!line.empty() && line[0] != '#')
                return true;
        }
        return false;
    };
    auto at = [&] { return "line " + std::to_string(lineNumber); };
    if (!nextLine() || line.rfind("wisp-strands 1", 0) != 0)
        return IoError{ path, at(), "not a wisp strand file (expected 'wisp-strands 1' on the first line)" };
    std::size_t strands = 0, points = 0;
    {
        if (!nextLine())
            return IoError{ path, at(), "the file ends before the 'strands S points P' line" };
        std::istringstream header(line);
        std::string w1, w2;
        if (!(header >> w1 >> strands >> w2 >> points) || w1 != "strands" || w2 != "points")
            return IoError{ path, at(), "expected 'strands S points P'" };
    }
    // Every point takes at least 6 characters of text: refuse a header that claims more than the file holds.
    if (points > size / 6 || strands > points)
        return IoError{ path, "line 2",
            "the header claims " + std::to_string(strands) + " strands and " + std::to_string(points)
                + " points, more than a file of " + std::to_string(size) + " bytes can hold" };
    HairCurves curves;
    curves.offsets.reserve(strands + 1);
    curves.positions.reserve(points);
    for (std::size_t s = 0; s < strands; ++s) {
        if (!nextLine())
            return IoError{ path, at(),
                "the file ends after " + std::to_string(s) + " of " + std::to_string(strands) + " strands" };
        std::istringstream row(line);
        std::size_t n = 0;
        // Compared with what is left, not as pointCount() + n > points: "-2" reads as 2^64 - 2,
        // and that sum wraps around (found by fuzz/fuzz_hair).
        if (!(row >> n) || n < 1 || n > points - curves.pointCount())
            return IoError{ path, at(), "a strand's point count is missing or exceeds the header's total" };
        const std::size_t index = curves.addStrand(static_cast<std::uint32_t>(n));
        for (glm::vec3& p : curves.strandForWrite(index)) {
            if (!(row >> p.x >> p.y >> p.z))
                return IoError{ path, at(),
                    "strand " + std::to_string(s) + " has fewer than " + std::to_string(n) + " points" };
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
                return IoError{ path, at(), "strand " + std::to_string(s) + " has a non-finite coordinate" };
        }
    }
    if (curves.pointCount() != points)
        return IoError{ path, at(),
            "the strands hold " + std::to_string(curves.pointCount()) + " points, the header says "
                + std::to_string(points) };
    return curves;
}

} // namespace wisp::io
