// OFF (ASCII). One vertex per line (x y z, then optional normal, colour, texture coordinates,
// ignored) and one face per line (n i1 ... in, then an optional colour, ignored); '#' starts a
// comment. The counts are checked against the bytes that follow them: a face claiming 4 billion
// corners must not make the reader push 4 billion indices.

#include "io/ReadFailure.h"
#include "io/mesh/FormatReaders.h"
#include "io/mesh/Tokenizer.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace wisp::io::mesh {

namespace {

class OffLines {
public:
    explicit OffLines(std::string_view text)
        : m_walker(text)
    {
    }

    // The next line with something on it besides a comment.
    bool next(std::vector<std::string_view>& tokens)
    {
        std::string_view line;
        while (m_walker.next(line)) {
            const std::size_t hash = line.find('#');
            if (hash != std::string_view::npos)
                line = line.substr(0, hash);
            splitTokens(line, tokens);
            if (!tokens.empty())
                return true;
        }
        return false;
    }

    std::string location() const { return lineAt(m_walker.lineNumber()); }
    std::size_t remainingBytes(std::size_t total) const { return total - std::min(total, m_walker.offset()); }

private:
    LineWalker m_walker;
};
} // namespace

void readOff(std::string_view bytes, MeshBuilder& builder)
{
    OffLines lines(bytes);
    std::vector<std::string_view> tokens;
    if (!lines.next(tokens))
        fail({}, "the file holds only comments and blank lines");

    // Keyword: [ST][C][N][4][n]OFF, optionally followed by BINARY.
    std::string_view keyword = tokens[0];
    if (keyword.size() < 3 || keyword.substr(keyword.size() - 3) != "OFF"
        || keyword.substr(0, keyword.size() - 3).find_first_not_of("STCN4n") != std::string_view::npos)
        fail(lines.location(), "not an OFF file: it should start with 'OFF', not " + quoted(keyword));
    const std::string_view prefix = keyword.substr(0, keyword.size() - 3);
    if (prefix.find('4') != std::string_view::npos || prefix.find('n') != std::string_view::npos)
        fail(lines.location(), "4-dimensional and n-dimensional OFF files are not supported");
    if (tokens.size() > 1 && tokens[1] == "BINARY")
        fail(lines.location(), "binary OFF is not supported; save the mesh as ASCII OFF, PLY or OBJ");

    // The counts may share the keyword's line.
    std::vector<std::string_view> counts(tokens.begin() + 1, tokens.end());
    if (counts.empty()) {
        if (!lines.next(tokens))
            fail(lines.location(), "the file ends before the vertex and face counts");
        counts = tokens;
    }
    std::int64_t vertexCount = 0;
    std::int64_t faceCount = 0;
    if (counts.size() < 2 || !parseInteger(counts[0], vertexCount) || !parseInteger(counts[1], faceCount)
        || vertexCount < 0 || faceCount < 0)
        fail(lines.location(), "expected the counts '<vertices> <faces> <edges>'");
    // A vertex line takes at least 5 bytes ("0 0 0"), a face line at least 2 ("0\n").
    const std::size_t remaining = lines.remainingBytes(bytes.size());
    if (static_cast<std::uint64_t>(vertexCount) > remaining / 5 + 1
        || static_cast<std::uint64_t>(faceCount) > remaining / 2 + 1)
        fail(lines.location(),
            "the header declares " + std::to_string(vertexCount) + " vertices and " + std::to_string(faceCount)
                + " faces, more than the " + std::to_string(remaining)
                + " bytes after it can hold: the file is truncated or the counts are wrong");
    if (vertexCount > static_cast<std::int64_t>(std::numeric_limits<std::uint32_t>::max()))
        fail(lines.location(), "too many vertices for Wisp to index");

    builder.mesh.positions.reserve(static_cast<std::size_t>(vertexCount));
    for (std::int64_t i = 0; i < vertexCount; ++i) {
        if (!lines.next(tokens))
            fail(lines.location(),
                "the file ends after " + std::to_string(i) + " of " + std::to_string(vertexCount) + " vertices");
        std::array<double, 3> xyz{};
        if (tokens.size() < 3)
            fail(lines.location(), "a vertex needs three coordinates");
        for (int k = 0; k < 3; ++k)
            if (!parseDouble(tokens[static_cast<std::size_t>(k)], xyz[static_cast<std::size_t>(k)]))
                fail(lines.location(),
                    "vertex coordinate " + quoted(tokens[static_cast<std::size_t>(k)]) + " is not a number");
        builder.mesh.positions.emplace_back(
            static_cast<float>(xyz[0]), static_cast<float>(xyz[1]), static_cast<float>(xyz[2]));
    }

    std::vector<std::uint32_t> corners;
    builder.mesh.triangles.reserve(static_cast<std::size_t>(faceCount));
    for (std::int64_t f = 0; f < faceCount; ++f) {
        if (!lines.next(tokens))
            fail(lines.location(),
                "the file ends after " + std::to_string(f) + " of " + std::to_string(faceCount) + " faces");
        std::int64_t n = 0;
        if (!parseInteger(tokens[0], n) || n < 0)
            fail(lines.location(), "a face should start with its number of corners, not " + quoted(tokens[0]));
        if (static_cast<std::uint64_t>(n) > tokens.size() - 1)
            fail(lines.location(),
                "face " + std::to_string(f) + " lists " + std::to_string(n) + " corners but the line holds only "
                    + std::to_string(tokens.size() - 1) + " numbers");
        corners.resize(static_cast<std::size_t>(n));
        for (std::size_t k = 0; k < corners.size(); ++k) {
            std::int64_t index = 0;
            if (!parseInteger(tokens[k + 1], index))
                fail(lines.location(), "face corner " + quoted(tokens[k + 1]) + " is not a vertex index");
            if (index < 0 || index >= vertexCount)
                fail(lines.location(),
                    "face " + std::to_string(f) + " refers to vertex " + std::to_string(index) + ", but the file has "
                        + std::to_string(vertexCount) + " vertices (numbered from 0)");
            corners[k] = static_cast<std::uint32_t>(index);
        }
        builder.addPolygon(corners.data(), corners.size());
    }
}

} // namespace wisp::io::mesh
