// Hair export for other tools: OBJ polylines and glTF 2.0 (.gltf with an embedded buffer, .glb).
//
// glTF layout (one buffer, every view 4-byte aligned):
//   view 0  hair POSITION     float32 vec3 per point (accessor with min/max, as glTF requires)
//   view 1  hair _WIDTH       float32 per point, metres, linear from the root width to the tip width
//   view 2  hair indices      uint32 pairs, one per segment (mode LINES)
//   view 3  head POSITION     (only with a head) float32 vec3 per vertex
//   view 4  head indices      (only with a head) uint32 triples (mode TRIANGLES)
// Meshes "hair" and "head" sit on nodes of the same names in scene 0.

#include "io/Base64.h"
#include "io/HairFilesInternal.h"
#include "io/gltf/GltfDocument.h"

#include <glm/common.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <limits>

namespace wisp::io::hair_detail {

namespace {

using nlohmann::json;

// glTF's numeric codes, named once for the reader and this writer (io/gltf/GltfDocument.h).
constexpr int kArrayBuffer = gltf::target::ArrayBuffer;
constexpr int kElementArrayBuffer = gltf::target::ElementArrayBuffer;
constexpr int kFloat = gltf::component::Float;
constexpr int kUnsignedInt = gltf::component::UnsignedInt;
constexpr int kModeLines = gltf::mode::Lines;
constexpr int kModeTriangles = gltf::mode::Triangles;

std::size_t nonEmptyStrands(const HairCurves& strands)
{
    std::size_t n = 0;
    for (std::size_t s = 0; s < strands.strandCount(); ++s)
        n += strands.pointsIn(s) > 0;
    return n;
}

std::optional<IoError> checkHead(const std::string& path, const TriangleMesh* head)
{
    if (!head)
        return std::nullopt;
    if (const std::string problem = validateMesh(*head); !problem.empty())
        return IoError{ path, "", "the head cannot be exported: " + problem };
    return std::nullopt;
}

// Builds the buffer and the JSON that describes it.
class GltfBuilder {
public:
    std::string buffer;
    json accessors = json::array();
    json bufferViews = json::array();

    // Appends the bytes written by `fill` as a new buffer view; returns its index.
    template <typename Fill> std::size_t addView(int target, Fill&& fill)
    {
        const std::size_t offset = buffer.size();
        fill(buffer);
        bufferViews.push_back({ { "buffer", 0 }, { "byteOffset", offset }, { "byteLength", buffer.size() - offset },
            { "target", target } });
        return bufferViews.size() - 1;
    }

    std::size_t addAccessor(std::size_t view, int componentType, std::size_t count, const char* type)
    {
        accessors.push_back(
            { { "bufferView", view }, { "componentType", componentType }, { "count", count }, { "type", type } });
        return accessors.size() - 1;
    }

    std::size_t addPositions(const std::vector<glm::vec3>& positions)
    {
        glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
        const std::size_t view = addView(kArrayBuffer, [&](std::string& out) {
            for (const glm::vec3& p : positions) {
                appendF32(out, p.x);
                appendF32(out, p.y);
                appendF32(out, p.z);
                lo = glm::min(lo, p);
                hi = glm::max(hi, p);
            }
        });
        const std::size_t accessor = addAccessor(view, kFloat, positions.size(), "VEC3");
        accessors[accessor]["min"] = { lo.x, lo.y, lo.z };
        accessors[accessor]["max"] = { hi.x, hi.y, hi.z };
        return accessor;
    }
};

} // namespace

Result<void> writeObjPolylines(const std::string& path, const HairCurves& strands, const HairExportOptions& options)
{
    if (std::optional<IoError> error = checkHead(path, options.head))
        return *error;
    std::string text;
    text.reserve(40 * strands.pointCount() + 16 * strands.pointCount());
    text += "# Wisp hair as OBJ polylines: " + std::to_string(nonEmptyStrands(strands)) + " strands, "
        + std::to_string(strands.pointCount()) + " points, coordinates in metres\n";
    text += "# one 'l' line per strand, root first"
        + std::string(options.head ? "; the head follows as object 'head'\n" : "\n");
    text += "o hair\n";
    char number[80];
    // %.9g round-trips a float exactly.
    for (const glm::vec3& p : strands.positions) {
        std::snprintf(number, sizeof number, "v %.9g %.9g %.9g\n", p.x, p.y, p.z);
        text += number;
    }
    for (std::size_t s = 0; s < strands.strandCount(); ++s) {
        const std::uint32_t n = strands.pointsIn(s);
        if (n == 0)
            continue;
        text += n == 1 ? "p" : "l"; // an OBJ line needs two points
        for (std::uint32_t i = 0; i < n; ++i) {
            text += ' ';
            text += std::to_string(std::uint64_t(strands.offsets[s]) + i + 1);
        }
        text += '\n';
    }
    if (const TriangleMesh* head = options.head) {
        text += "o head\n";
        for (const glm::vec3& p : head->positions) {
            std::snprintf(number, sizeof number, "v %.9g %.9g %.9g\n", p.x, p.y, p.z);
            text += number;
        }
        const std::uint64_t base = strands.pointCount() + 1;
        for (const glm::uvec3& t : head->triangles)
            text += "f " + std::to_string(base + t.x) + " " + std::to_string(base + t.y) + " "
                + std::to_string(base + t.z) + "\n";
    }
    return writeBytesAtomically(path, text);
}

Result<void> writeGltf(
    const std::string& path, const HairCurves& strands, const HairExportOptions& options, bool binary)
{
    if (!std::isfinite(options.rootWidthMetres) || !std::isfinite(options.tipWidthMetres)
        || options.rootWidthMetres < 0.0f || options.tipWidthMetres < 0.0f)
        return IoError{ path, "",
            "strand widths must be finite and not negative (root " + std::to_string(options.rootWidthMetres)
                + " m, tip " + std::to_string(options.tipWidthMetres) + " m)" };
    if (std::optional<IoError> error = checkHead(path, options.head))
        return *error;
    std::size_t segments = 0;
    for (std::size_t s = 0; s < strands.strandCount(); ++s)
        segments += strands.pointsIn(s) > 1 ? strands.pointsIn(s) - 1 : 0;
    if (segments == 0)
        return IoError{ path, "", "no strand has two points: there are no segments to export" };

    GltfBuilder b;
    const std::size_t hairPositions = b.addPositions(strands.positions);
    const std::size_t widthView = b.addView(kArrayBuffer, [&](std::string& out) {
        for (std::size_t s = 0; s < strands.strandCount(); ++s) {
            const std::uint32_t n = strands.pointsIn(s);
            for (std::uint32_t i = 0; i < n; ++i) {
                const float t = n > 1 ? float(i) / float(n - 1) : 0.0f;
                appendF32(out, options.rootWidthMetres + (options.tipWidthMetres - options.rootWidthMetres) * t);
            }
        }
    });
    const std::size_t widths = b.addAccessor(widthView, kFloat, strands.pointCount(), "SCALAR");
    const std::size_t lineView = b.addView(kElementArrayBuffer, [&](std::string& out) {
        for (std::size_t s = 0; s < strands.strandCount(); ++s)
            for (std::uint32_t i = strands.offsets[s]; i + 1 < strands.offsets[s + 1]; ++i) {
                appendU32(out, i);
                appendU32(out, i + 1);
            }
    });
    const std::size_t lines = b.addAccessor(lineView, kUnsignedInt, 2 * segments, "SCALAR");

    json meshes = json::array();
    json nodes = json::array();
    meshes.push_back({ { "name", "hair" },
        { "primitives",
            json::array({ { { "attributes", { { "POSITION", hairPositions }, { "_WIDTH", widths } } },
                { "indices", lines }, { "mode", kModeLines } } }) } });
    nodes.push_back({ { "name", "hair" }, { "mesh", 0 },
        { "extras",
            { { "strandCount", nonEmptyStrands(strands) }, { "rootWidthMetres", options.rootWidthMetres },
                { "tipWidthMetres", options.tipWidthMetres } } } });
    if (const TriangleMesh* head = options.head) {
        const std::size_t headPositions = b.addPositions(head->positions);
        const std::size_t triangleView = b.addView(kElementArrayBuffer, [&](std::string& out) {
            for (const glm::uvec3& t : head->triangles) {
                appendU32(out, t.x);
                appendU32(out, t.y);
                appendU32(out, t.z);
            }
        });
        const std::size_t triangles = b.addAccessor(triangleView, kUnsignedInt, 3 * head->triangles.size(), "SCALAR");
        meshes.push_back({ { "name", "head" },
            { "primitives",
                json::array({ { { "attributes", { { "POSITION", headPositions } } }, { "indices", triangles },
                    { "mode", kModeTriangles } } }) } });
        nodes.push_back({ { "name", "head" }, { "mesh", 1 } });
    }
    json scenes = json::array();
    json sceneNodes = json::array();
    for (std::size_t i = 0; i < nodes.size(); ++i)
        sceneNodes.push_back(i);
    scenes.push_back({ { "nodes", sceneNodes } });

    json gltf;
    gltf["asset"] = { { "version", "2.0" }, { "generator", "Wisp" } };
    gltf["scene"] = 0;
    gltf["scenes"] = scenes;
    gltf["nodes"] = nodes;
    gltf["meshes"] = meshes;
    gltf["accessors"] = b.accessors;
    gltf["bufferViews"] = b.bufferViews;
    json buffer = { { "byteLength", b.buffer.size() } };
    if (!binary)
        buffer["uri"] = "data:application/octet-stream;base64,"
            + base64Encode({ reinterpret_cast<const std::uint8_t*>(b.buffer.data()), b.buffer.size() });
    gltf["buffers"] = json::array({ buffer });

    if (!binary)
        return writeBytesAtomically(path, gltf.dump(1) + "\n");

    // GLB: 12-byte header, a JSON chunk padded with spaces, a BIN chunk padded with zeros.
    std::string jsonText = gltf.dump();
    jsonText.resize((jsonText.size() + 3) / 4 * 4, ' ');
    std::string& bin = b.buffer;
    bin.resize((bin.size() + 3) / 4 * 4, '\0');
    const std::uint64_t total = 12 + 8 + jsonText.size() + 8 + bin.size();
    if (total > std::numeric_limits<std::uint32_t>::max())
        return IoError{ path, "",
            "the hair is too large for a .glb file (" + std::to_string(total) + " bytes; .glb holds at most 4 GiB)" };
    std::string glb;
    glb.reserve(total);
    appendU32(glb, 0x46546C67); // "glTF"
    appendU32(glb, 2);
    appendU32(glb, static_cast<std::uint32_t>(total));
    appendU32(glb, static_cast<std::uint32_t>(jsonText.size()));
    appendU32(glb, 0x4E4F534A); // "JSON"
    glb += jsonText;
    appendU32(glb, static_cast<std::uint32_t>(bin.size()));
    appendU32(glb, 0x004E4942); // "BIN\0"
    glb += bin;
    return writeBytesAtomically(path, glb);
}

} // namespace wisp::io::hair_detail
