// Wavefront OBJ: `v x y z` vertices (a fourth weight or a colour after them is ignored) and `f`
// faces whose corners are `v`, `v/vt`, `v//vn` or `v/vt/vn`; a negative index counts back from
// the vertices read so far, a positive one may name any vertex of the file. Texture coordinates,
// normals, groups, smoothing and materials are not needed for a collider and are skipped; no
// material library is opened (`mtllib /dev/zero` or a FIFO beside the file would block a reader
// that did), only named in a warning. `l` and `p` elements are counted and reported.

#include "io/ReadFailure.h"
#include "io/mesh/FormatReaders.h"
#include "io/mesh/Tokenizer.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace wisp::io::mesh {

namespace {

// A coordinate a float can hold: nan, inf and anything beyond the float range are refused.
float finiteCoordinate(std::string_view token, std::size_t line)
{
    double value = 0.0;
    if (!parseDouble(token, value))
        fail(lineAt(line), "vertex coordinate " + quoted(token) + " is not a number");
    if (!std::isfinite(value) || !std::isfinite(static_cast<float>(value)))
        fail(lineAt(line), "vertex coordinate " + quoted(token) + " is not a finite number");
    return static_cast<float>(value);
}

struct ForwardReference {
    std::size_t line = 0;
    std::int64_t index = 0; // as written (positive), checked once every vertex is known
};

} // namespace

void readObj(std::string_view bytes, MeshBuilder& builder, std::vector<std::string>& warnings)
{
    LineWalker lines(bytes);
    std::string_view line;
    std::vector<std::string_view> tokens;
    std::vector<std::uint32_t> corners;
    std::vector<ForwardReference> forward;
    std::vector<std::string> materialLibraries;
    std::size_t faceLines = 0;
    std::size_t lineElements = 0;
    std::size_t pointElements = 0;
    std::vector<glm::vec3>& positions = builder.mesh.positions;

    while (lines.next(line)) {
        splitTokens(line, tokens);
        if (tokens.empty() || tokens[0].front() == '#')
            continue;
        const std::string_view keyword = tokens[0];
        const std::size_t at = lines.lineNumber();
        if (keyword == "v") {
            if (tokens.size() < 4)
                fail(lineAt(at), "a vertex line needs three coordinates");
            if (positions.size() >= std::numeric_limits<std::uint32_t>::max())
                fail(lineAt(at), "too many vertices for Wisp to index");
            positions.emplace_back(
                finiteCoordinate(tokens[1], at), finiteCoordinate(tokens[2], at), finiteCoordinate(tokens[3], at));
        } else if (keyword == "f") {
            ++faceLines;
            corners.clear();
            for (std::size_t k = 1; k < tokens.size(); ++k) {
                const std::string_view corner = tokens[k].substr(0, tokens[k].find('/'));
                std::int64_t index = 0;
                if (!parseInteger(corner, index))
                    fail(lineAt(at), "face corner " + quoted(tokens[k]) + " does not start with a vertex index");
                if (index == 0)
                    fail(lineAt(at), "a face uses vertex index 0, but OBJ numbers vertices from 1");
                const auto soFar = static_cast<std::int64_t>(positions.size());
                const std::int64_t resolved = index < 0 ? soFar + index + 1 : index;
                if (resolved < 1 || (index < 0 && resolved > soFar))
                    fail(lineAt(at),
                        "a face refers to vertex " + std::to_string(index) + ", but the file has "
                            + std::to_string(soFar) + " vertices before this line");
                if (resolved > std::numeric_limits<std::uint32_t>::max())
                    fail(lineAt(at), "a face refers to vertex " + std::to_string(index) + ", more than Wisp can index");
                if (resolved > soFar)
                    forward.push_back({ at, index });
                corners.push_back(static_cast<std::uint32_t>(resolved - 1));
            }
            builder.addPolygon(corners.data(), corners.size());
        } else if (keyword == "l") {
            ++lineElements;
        } else if (keyword == "p") {
            ++pointElements;
        } else if (keyword == "mtllib") {
            // The names as written: from the first to the last, spaces between them kept.
            const std::size_t first = static_cast<std::size_t>(tokens[1 % tokens.size()].data() - line.data());
            const std::size_t end = static_cast<std::size_t>(tokens.back().data() + tokens.back().size() - line.data());
            materialLibraries.emplace_back(tokens.size() > 1 ? line.substr(first, end - first) : std::string_view());
        }
    }
    // Faces may name vertices that come later in the file; now that every vertex is known, the
    // first one that names a vertex the file lacks is the error.
    for (const ForwardReference& ref : forward)
        if (ref.index > static_cast<std::int64_t>(positions.size()))
            fail(lineAt(ref.line),
                "a face refers to vertex " + std::to_string(ref.index) + ", but the file has "
                    + std::to_string(positions.size()) + " vertices");

    if (lineElements > 0 || pointElements > 0)
        warnings.push_back("ignored " + plural(lineElements, "line element ('l')", "line elements ('l')") + " and "
            + plural(pointElements, "point element ('p')", "point elements ('p')"));
    for (const std::string& library : materialLibraries)
        warnings.push_back("ignored the material library '" + library + "': Wisp reads no materials");

    if (builder.mesh.triangles.empty()) {
        std::string why = "the file has " + plural(positions.size(), "vertex", "vertices") + " but no faces";
        if (lineElements > 0 || pointElements > 0)
            why += " (only " + plural(lineElements, "line", "lines") + " and "
                + plural(pointElements, "point", "points") + ", which are not a surface)";
        else if (faceLines > 0)
            why += " with 3 distinct corners";
        fail({}, why + "; a head mesh needs triangles or polygons");
    }
}

} // namespace wisp::io::mesh
