// STL, binary and ASCII. A binary STL is exactly 84 + 50 n bytes, n being the count at byte 80;
// anything else must be ASCII ('solid ... facet ... outer loop ... vertex x y z'). STL triangles
// carry no indices, so corners at equal coordinates are welded into one vertex (in the order they
// first appear; -0 and +0 are one corner), which is what makes the mesh a connected surface.

#include "io/ReadFailure.h"
#include "io/mesh/ByteReader.h"
#include "io/mesh/FormatReaders.h"
#include "io/mesh/PositionWelder.h"
#include "io/mesh/Tokenizer.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace wisp::io::mesh {

namespace {

constexpr std::size_t kHeaderBytes = 84;
constexpr std::size_t kRecordBytes = 50; // normal, three corners (float32 x 12), 2 attribute bytes

// Makes triangles of corners, welded into vertices by position.
class CornerWelder {
public:
    explicit CornerWelder(MeshBuilder& builder)
        : m_builder(builder)
    {
    }

    void addTriangle(const std::array<glm::vec3, 3>& corners)
    {
        std::vector<glm::vec3>& positions = m_builder.mesh.positions;
        const std::array<std::uint32_t, 3> v{ m_welder.indexOf(corners[0], positions),
            m_welder.indexOf(corners[1], positions), m_welder.indexOf(corners[2], positions) };
        m_builder.addPolygon(v.data(), v.size());
    }

private:
    MeshBuilder& m_builder;
    PositionWelder m_welder;
};

bool isBinaryStl(std::string_view bytes, std::uint32_t& triangleCount)
{
    if (bytes.size() < kHeaderBytes)
        return false;
    triangleCount = loadLittle<std::uint32_t>(bytes.data() + 80);
    return bytes.size() == kHeaderBytes + kRecordBytes * static_cast<std::uint64_t>(triangleCount);
}

void readBinaryStl(std::string_view bytes, std::uint32_t triangleCount, CornerWelder& welder)
{
    for (std::uint32_t t = 0; t < triangleCount; ++t) {
        const std::size_t record = kHeaderBytes + kRecordBytes * static_cast<std::size_t>(t);
        std::array<glm::vec3, 3> corners;
        for (std::size_t k = 0; k < 9; ++k) { // three corners after the 12-byte facet normal
            const std::size_t at = record + 12 + 4 * k;
            const float value = loadLittle<float>(bytes.data() + at);
            if (!std::isfinite(value))
                fail(byteAt(at), "triangle " + std::to_string(t) + " has a non-finite coordinate");
            corners[k / 3][static_cast<int>(k % 3)] = value;
        }
        welder.addTriangle(corners);
    }
}

bool equalsIgnoringCase(std::string_view token, std::string_view lower)
{
    return token.size() == lower.size() && std::equal(token.begin(), token.end(), lower.begin(), [](char a, char b) {
        return (a >= 'A' && a <= 'Z' ? static_cast<char>(a - 'A' + 'a') : a) == b;
    });
}

// After each `outer loop` line come three `vertex x y z` lines; everything else (facet normals,
// endloop, endfacet, solid names) carries nothing a collider needs.
void readAsciiStl(std::string_view bytes, CornerWelder& welder)
{
    LineWalker lines(bytes);
    std::string_view line;
    std::vector<std::string_view> tokens;
    while (lines.next(line)) {
        splitTokens(line, tokens);
        if (tokens.empty() || !equalsIgnoringCase(tokens[0], "outer"))
            continue;
        std::array<glm::vec3, 3> corners;
        for (glm::vec3& corner : corners) {
            if (!lines.next(line))
                fail(lineAt(lines.lineNumber()), "the file ends inside a facet");
            splitTokens(line, tokens);
            if (tokens.size() < 4 || !equalsIgnoringCase(tokens[0], "vertex"))
                fail(lineAt(lines.lineNumber()), "expected 'vertex x y z'");
            for (int c = 0; c < 3; ++c) {
                const std::string_view token = tokens[static_cast<std::size_t>(c) + 1];
                double value = 0.0;
                if (!parseDouble(token, value))
                    fail(lineAt(lines.lineNumber()), "vertex coordinate " + quoted(token) + " is not a number");
                if (!std::isfinite(value) || !std::isfinite(static_cast<float>(value)))
                    fail(lineAt(lines.lineNumber()), "vertex coordinate " + quoted(token) + " is not a finite number");
                corner[c] = static_cast<float>(value);
            }
        }
        welder.addTriangle(corners);
    }
}

} // namespace

void readStl(std::string_view bytes, MeshBuilder& builder, std::vector<std::string>&)
{
    CornerWelder welder(builder);
    std::uint32_t triangleCount = 0;
    if (isBinaryStl(bytes, triangleCount)) {
        builder.mesh.triangles.reserve(triangleCount); // the file's size vouches for the count
        readBinaryStl(bytes, triangleCount, welder);
    } else {
        // Not binary by size, so it must be ASCII, which starts with "solid" and holds no NUL
        // bytes. Anything else is a binary STL that is cut short or corrupt.
        const std::size_t firstChar = std::min(bytes.size(), bytes.find_first_not_of(" \t\r\n"));
        const bool looksAscii
            = bytes.substr(firstChar, 5) == "solid" && bytes.substr(0, 1024).find('\0') == std::string_view::npos;
        if (!looksAscii) {
            if (bytes.size() < kHeaderBytes)
                fail({},
                    "the file is too short for a binary STL (" + std::to_string(bytes.size())
                        + " bytes; the header alone takes 84) and is not an ASCII STL (which starts with 'solid')");
            fail(byteAt(80),
                "binary STL header says " + std::to_string(triangleCount) + " triangles, which take "
                    + std::to_string(kHeaderBytes + kRecordBytes * static_cast<std::uint64_t>(triangleCount))
                    + " bytes, but the file has " + std::to_string(bytes.size()) + ": it is truncated or corrupt");
        }
        readAsciiStl(bytes, welder);
    }
    if (builder.mesh.triangles.empty())
        fail({},
            "no triangles found: the file is not an STL ('solid ... facet ... outer loop ... vertex') or holds only "
            "degenerate facets");
}

} // namespace wisp::io::mesh
