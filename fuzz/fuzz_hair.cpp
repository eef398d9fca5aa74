// Fuzz target: io::readHair (cyHair .hair, USC-HairSalon .data) and io::readStrandText
// (wisp-strands text). The format follows the content, so seeds are the files as they are:
// "HAIR" at the start is cyHair, "wisp-strands" is strand text, anything else is read as .data
// (which has no magic). Checks what every reader promises: consistent offsets, finite points.

#include "fuzz/FuzzSupport.h"
#include "io/HairFiles.h"
#include "io/StrandText.h"

#include <cmath>
#include <cstring>

namespace {

void checkStrands(const wisp::HairCurves& strands)
{
    if (strands.offsets.empty() || strands.offsets.front() != 0 || strands.offsets.back() != strands.pointCount())
        wisp::fuzz::fail("strand offsets do not cover the points");
    for (std::size_t i = 0; i + 1 < strands.offsets.size(); ++i)
        if (strands.offsets[i] > strands.offsets[i + 1])
            wisp::fuzz::fail("strand offsets decrease at strand " + std::to_string(i));
    for (const glm::vec3& p : strands.positions)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            wisp::fuzz::fail("a reader returned a non-finite point");
}

bool startsWith(const std::uint8_t* data, std::size_t size, const char* magic)
{
    const std::size_t n = std::strlen(magic);
    return size >= n && std::memcmp(data, magic, n) == 0;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    if (startsWith(data, size, "wisp-strands")) {
        const std::string path = wisp::fuzz::writeInput("strands.txt", data, size);
        if (const wisp::io::Result<wisp::HairCurves> read = wisp::io::readStrandText(path))
            checkStrands(read.value());
        return 0;
    }
    const std::string path
        = wisp::fuzz::writeInput(startsWith(data, size, "HAIR") ? "strands.hair" : "strands.data", data, size);
    if (const wisp::io::Result<wisp::io::HairReadResult> read = wisp::io::readHair(path))
        checkStrands(read.value().strands);
    return 0;
}
