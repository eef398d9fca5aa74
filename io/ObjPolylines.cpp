// Reading OBJ polylines (hair as Wisp and other tools write it): `v x y z` vertices and one `l`
// line per strand; faces (a head written beside the hair), `p` points and everything else are
// skipped, with a warning for what could have been meant as hair.

#include "io/HairFilesInternal.h"
#include "io/mesh/Tokenizer.h"

#include <cmath>
#include <string_view>

namespace wisp::io::hair_detail {

Result<HairReadResult> readObjPolylines(const std::string& path)
{
    Result<std::string> file = readRegularFile(path, kHairFileRules);
    if (!file)
        return file.error();
    std::vector<glm::vec3> vertices;
    HairReadResult result;
    std::vector<std::vector<std::int64_t>> lines; // raw indices, resolved once all vertices are known
    std::vector<std::size_t> lineNumbers;
    std::size_t faces = 0, points = 0, shortLines = 0;
    // The text mesh readers' tokenizer (io/mesh/Tokenizer.h): the same lines, tokens and numbers.
    mesh::LineWalker walker(file.value());
    std::vector<std::string_view> tokens;
    for (std::string_view line; walker.next(line);) {
        mesh::splitTokens(line, tokens);
        if (tokens.empty())
            continue;
        const std::string where = "line " + std::to_string(walker.lineNumber());
        const std::string_view keyword = tokens[0];
        if (keyword == "v") {
            glm::vec3 p;
            for (std::size_t c = 0; c < 3; ++c) {
                const std::string_view token = c + 1 < tokens.size() ? tokens[c + 1] : std::string_view{};
                double value = 0.0;
                if (!mesh::parseDouble(token, value))
                    return IoError{ path, where, "a vertex needs 3 numbers; '" + std::string(token) + "' is not one" };
                p[static_cast<glm::length_t>(c)] = static_cast<float>(value);
                if (!std::isfinite(p[static_cast<glm::length_t>(c)]))
                    return IoError{ path, where, "a vertex coordinate is not a finite number" };
            }
            vertices.push_back(p);
        } else if (keyword == "l") {
            std::vector<std::int64_t> indices;
            for (std::size_t t = 1; t < tokens.size(); ++t) {
                const std::string_view token = tokens[t].substr(0, tokens[t].find('/')); // "v/vt": the vertex
                std::int64_t index = 0;
                if (!mesh::parseInteger(token, index) || index == 0)
                    return IoError{ path, where, "'" + std::string(token) + "' is not a vertex number" };
                // A negative index counts back from the vertices read so far (the OBJ spec).
                if (index < 0)
                    index += static_cast<std::int64_t>(vertices.size()) + 1;
                indices.push_back(index);
            }
            if (indices.size() < 2) {
                ++shortLines;
                continue;
            }
            lines.push_back(std::move(indices));
            lineNumbers.push_back(walker.lineNumber());
        } else if (keyword == "f") {
            ++faces;
        } else if (keyword == "p") {
            ++points;
        }
    }
    HairCurves& strands = result.strands;
    for (std::size_t l = 0; l < lines.size(); ++l) {
        for (std::int64_t index : lines[l]) {
            if (index < 1 || index > static_cast<std::int64_t>(vertices.size()))
                return IoError{ path, "line " + std::to_string(lineNumbers[l]),
                    "vertex " + std::to_string(index) + " does not exist (the file has "
                        + std::to_string(vertices.size()) + ")" };
            strands.positions.push_back(vertices[static_cast<std::size_t>(index - 1)]);
        }
        strands.offsets.push_back(static_cast<std::uint32_t>(strands.positions.size()));
    }
    if (strands.strandCount() == 0)
        return IoError{ path, "", "no strands: an OBJ polyline is an 'l' line of two vertices or more" };
    if (faces > 0)
        result.warnings.push_back(
            "skipped " + std::to_string(faces) + " faces (a mesh, such as a head written beside the hair)");
    if (points > 0)
        result.warnings.push_back("skipped " + std::to_string(points) + " 'p' points (strands of one point)");
    if (shortLines > 0)
        result.warnings.push_back("skipped " + std::to_string(shortLines) + " 'l' lines of fewer than two vertices");
    return result;
}

Result<HairReadResult> readGltfStrands(const std::string& path)
{
    Result<GltfLines> read = readGltfLines(path);
    if (!read)
        return read.error();
    GltfLines lines = std::move(read).value();
    HairReadResult result;
    result.strands = std::move(lines.strands);
    result.widthsMetres = std::move(lines.widthsMetres);
    result.warnings = std::move(lines.warnings);
    return result;
}

} // namespace wisp::io::hair_detail
