#include "io/GltfReader.h"

#include "io/GltfSchema.h"
#include "io/JsonErrors.h"
#include "io/ReadFailure.h"
#include "io/RegularFile.h"
#include "io/gltf/GlbContainer.h"
#include "io/gltf/GltfAccessors.h"
#include "io/gltf/GltfDocument.h"
#include "io/gltf/SceneMerger.h"

#include <nlohmann/json.hpp>

#include <bit>
#include <cmath>
#include <exception>
#include <filesystem>
#include <new>
#include <set>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace wisp::io {

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

// glTF stores numbers little-endian; the accessor reader copies them straight into host numbers.
static_assert(std::endian::native == std::endian::little, "the glTF reader assumes a little-endian host");

// A file nested thousands deep is garbage (real glTF nests about 8 deep), and tearing down such a
// JSON value recurses once per level on the reading thread's stack.
constexpr std::size_t maxJsonDepth = 128;

// Offset of the first bracket nested deeper than `limit`, or npos. Strings are skipped, so
// brackets inside names and data URIs do not count.
std::size_t tooDeepAt(std::string_view text, std::size_t limit)
{
    std::size_t depth = 0;
    return findOutsideJsonStrings(text, [&](std::size_t, char c) {
        if (c == '[' || c == '{')
            return ++depth > limit;
        if ((c == ']' || c == '}') && depth > 0)
            --depth;
        return false;
    });
}

// Where byte `offset` of the JSON is, as the artist would find it: a line and column in a text
// .gltf, a byte of the file in a .glb.
std::string jsonPlace(std::string_view text, std::size_t offset, bool binary, std::size_t jsonOffset)
{
    offset = std::min(offset, text.size());
    if (binary)
        return byteAt(jsonOffset + offset);
    return lineAndColumn(text, offset);
}

// Required extensions that change only how a surface looks, or that this reader handles
// (KHR_mesh_quantization: integer positions, read by readAccessor). Any other required
// extension may change what the geometry is, so reading on would give a wrong head.
bool requiredExtensionIsHarmless(const std::string& name)
{
    static const std::set<std::string> harmless = {
        "KHR_mesh_quantization",
        "KHR_texture_transform",
        "KHR_texture_basisu",
        "EXT_texture_webp",
        "EXT_texture_avif",
        "KHR_lights_punctual",
        "KHR_materials_variants",
    };
    return harmless.count(name) != 0 || name.rfind("KHR_materials_", 0) == 0;
}

void refuseUnsupportedExtensions(const Json& root)
{
    const auto it = root.find("extensionsRequired");
    if (it == root.end())
        return;
    if (!it->is_array())
        fail("extensionsRequired", "must be a list of extension names");
    for (const Json& entry : *it) {
        if (!entry.is_string())
            fail("extensionsRequired", "must be a list of extension names");
        const std::string name = entry.get<std::string>();
        if (name == "KHR_draco_mesh_compression")
            fail("extensionsRequired",
                "uses Draco mesh compression (KHR_draco_mesh_compression), which Wisp cannot read; "
                "export the head without Draco");
        if (name == "EXT_meshopt_compression" || name == "KHR_meshopt_compression")
            fail("extensionsRequired",
                "uses meshopt compression (" + name + "), which Wisp cannot read; export the head without it");
        if (!requiredExtensionIsHarmless(name))
            fail("extensionsRequired",
                "requires the glTF extension " + name + ", which Wisp cannot read; export the head without it");
    }
}

// Parses the JSON and checks it against the parts of the schema that make geometry.
Json parsedJson(std::string_view text, bool binary, std::size_t jsonOffset, const fs::path& folder,
    std::vector<std::string>& warnings)
{
    if (const std::size_t deep = tooDeepAt(text, maxJsonDepth); deep != std::string_view::npos)
        fail(jsonPlace(text, deep, binary, jsonOffset),
            "the JSON nests more than " + std::to_string(maxJsonDepth) + " levels deep; no glTF file needs that");
    if (text.substr(0, 3) == "\xEF\xBB\xBF")
        warnings.push_back("the JSON starts with a byte-order mark, which glTF forbids; ignored it");

    Json root;
    try {
        root = Json::parse(text.begin(), text.end());
    } catch (const Json::parse_error& e) {
        fail(jsonPlace(text, e.byte == 0 ? 0 : e.byte - 1, binary, jsonOffset),
            "invalid JSON: " + withoutJsonPrefix(e.what()));
    } catch (const Json::exception& e) { // out_of_range.406: a number that overflows a double
        const JsonFailure failure = describeJsonFailure(text, e);
        fail(binary ? std::string() : failure.place, "invalid JSON: " + failure.message);
    }
    if (!root.is_object())
        fail({}, "the JSON is not an object, so this is not a glTF file");

    const auto asset = root.find("asset");
    if (asset == root.end() || !asset->is_object())
        fail("asset", "missing: every glTF file has an 'asset' object with its version");
    const auto version = asset->find("version");
    if (version == asset->end() || !version->is_string())
        fail("asset.version", "missing: every glTF file states its version");
    const std::string versionText = version->get<std::string>();
    if (versionText.rfind("2.", 0) != 0)
        fail("asset.version",
            "glTF " + versionText + "; Wisp reads glTF 2.0"
                + (versionText.rfind("1.", 0) == 0 ? ": re-export the head as glTF 2.0" : ""));

    refuseUnsupportedExtensions(root);
    if (const std::optional<GltfSchemaProblem> problem = checkGltfSchema(root, folder, warnings))
        fail(problem->keyPath, problem->message);
    return root;
}

// The file at `path` read once: the container split (the magic decides, so that a binary file
// misnamed .gltf still reads; a .glb without it goes to the container check, which says what is
// wrong), the JSON parsed and checked once, the geometry parts and buffers loaded. Throws
// io::ReadFailure. Meshes and strands both read through it.
gltf::Document readDocumentOf(const std::string& path, std::vector<std::string>& warnings)
{
    const std::string bytes = readRegularFileOrFail(path, { kMaxMeshFileBytes, "glTF", false });
    const bool namedGlb = lowerExtension(path) == "glb";
    const bool binary = namedGlb || gltf::startsWithGlbMagic(bytes);
    std::error_code ec;
    const fs::path folder = fs::absolute(fs::path(path), ec).parent_path();
    gltf::GlbParts parts;
    if (binary)
        parts = gltf::splitGlb(bytes, warnings);
    else
        parts.json = bytes;
    const Json root = parsedJson(parts.json, binary, parts.jsonOffset, folder, warnings);
    if (binary && !namedGlb)
        warnings.push_back("this is a binary glTF (GLB) file named .gltf; read it as binary");
    return gltf::readDocument(root, binary, parts.bin, folder, warnings);
}

} // namespace

namespace {

// The strands of every LINES and LINE_STRIP primitive, in mesh and primitive order: a LINES
// primitive's index pairs are chained while each segment starts where the last one ended (Wisp's
// writer gives each strand's segments in order), a new strand begins where one does not.
GltfLines readLines(const gltf::Document& model, std::vector<std::string>& warnings)
{
    GltfLines out;
    bool widthsEverywhere = true;
    for (std::size_t m = 0; m < model.meshes.size(); ++m) {
        for (std::size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
            const gltf::Primitive& primitive = model.meshes[m].primitives[p];
            const std::string location = gltf::indexed("meshes", m) + "." + gltf::indexed("primitives", p);
            if (primitive.mode != gltf::mode::Lines && primitive.mode != gltf::mode::LineStrip)
                continue;
            const auto position = primitive.attributes.find("POSITION");
            if (position == primitive.attributes.end())
                fail(location, "a LINES primitive without POSITION");
            const gltf::AccessorValues positions
                = gltf::readAccessor(model, position->second, "POSITION of " + location);
            if (positions.components != 3)
                fail(location, "POSITION is not VEC3");
            for (double v : positions.values)
                if (!std::isfinite(static_cast<float>(v)))
                    fail(location, "a POSITION is not a finite number");
            std::vector<double> widths;
            if (const auto width = primitive.attributes.find("_WIDTH"); width != primitive.attributes.end()) {
                gltf::AccessorValues w = gltf::readAccessor(model, width->second, "_WIDTH of " + location);
                if (w.components != 1 || w.count != positions.count)
                    fail(location, "_WIDTH must be one SCALAR per POSITION (" + std::to_string(positions.count) + ")");
                for (double v : w.values)
                    if (!(v >= 0.0) || !std::isfinite(static_cast<float>(v)))
                        fail(location, "a _WIDTH is negative or not a finite number");
                widths = std::move(w.values);
            } else {
                widthsEverywhere = false;
            }
            std::vector<std::uint32_t> indices;
            if (primitive.indices != gltf::kAbsent) {
                const gltf::AccessorValues values
                    = gltf::readAccessor(model, primitive.indices, "indices of " + location);
                indices.reserve(values.values.size());
                for (std::size_t i = 0; i < values.values.size(); ++i) {
                    const double v = values.values[i];
                    if (!(v >= 0.0 && v < static_cast<double>(positions.count)) || std::floor(v) != v)
                        fail(location,
                            "index " + std::to_string(i) + " is out of range: the POSITION accessor has "
                                + plural(positions.count, "vertex", "vertices"));
                    indices.push_back(static_cast<std::uint32_t>(v));
                }
            } else {
                for (std::size_t i = 0; i < positions.count; ++i)
                    indices.push_back(static_cast<std::uint32_t>(i));
            }
            auto point = [&](std::uint32_t i) {
                out.strands.positions.push_back(glm::vec3(static_cast<float>(positions.values[3 * i]),
                    static_cast<float>(positions.values[3 * i + 1]), static_cast<float>(positions.values[3 * i + 2])));
                out.widthsMetres.push_back(widths.empty() ? 0.0f : static_cast<float>(widths[i]));
            };
            auto endStrand = [&] {
                if (out.strands.positions.size() > out.strands.offsets.back())
                    out.strands.offsets.push_back(static_cast<std::uint32_t>(out.strands.positions.size()));
            };
            if (primitive.mode == gltf::mode::LineStrip) {
                for (std::uint32_t i : indices)
                    point(i);
                endStrand();
                continue;
            }
            if (indices.size() % 2 != 0)
                fail(location, "LINES needs an even number of indices, not " + std::to_string(indices.size()));
            for (std::size_t k = 0; k < indices.size(); k += 2) {
                if (k == 0 || indices[k] != indices[k - 1]) {
                    endStrand();
                    point(indices[k]);
                }
                point(indices[k + 1]);
            }
            endStrand();
        }
    }
    for (std::size_t n = 0; n < model.nodes.size(); ++n) {
        const gltf::Node& node = model.nodes[n];
        const bool transforms
            = !node.matrix.empty() || !node.translation.empty() || !node.rotation.empty() || !node.scale.empty();
        if (transforms && node.mesh >= 0 && static_cast<std::size_t>(node.mesh) < model.meshes.size())
            for (const gltf::Primitive& p : model.meshes[static_cast<std::size_t>(node.mesh)].primitives)
                if (p.mode == gltf::mode::Lines || p.mode == gltf::mode::LineStrip) {
                    warnings.push_back(gltf::indexed("nodes", n) + " transforms its lines; strands are read as stored");
                    break;
                }
    }
    if (out.strands.strandCount() == 0)
        fail({}, "no strands: the file has no LINES or LINE_STRIP primitive");
    if (!widthsEverywhere)
        out.widthsMetres.clear();
    return out;
}

// Runs one whole read of `path` and turns whatever it throws into the error the reader returns:
// a ReadFailure names its place in the file, anything else (memory, a JSON parser's surprise)
// is said without one. Every glTF read, heads and strands alike, ends here, so none can throw.
template <typename T, typename ReadFn> Result<T> readGuarded(const std::string& path, ReadFn&& read)
{
    try {
        return read();
    } catch (const ReadFailure& failure) {
        return IoError{ path, failure.location, failure.message };
    } catch (const std::bad_alloc&) {
        return IoError{ path, {}, "not enough memory to read this glTF file" };
    } catch (const std::exception& e) {
        return IoError{ path, {}, "unexpected error while reading: " + withoutJsonPrefix(e.what()) };
    }
}

} // namespace

Result<GltfLines> readGltfLines(const std::string& path)
{
    return readGuarded<GltfLines>(path, [&] {
        std::vector<std::string> warnings;
        const gltf::Document document = readDocumentOf(path, warnings);
        GltfLines lines = readLines(document, warnings);
        lines.warnings = std::move(warnings);
        return lines;
    });
}

Result<MeshReadResult> readGltf(const std::string& path)
{
    return readGuarded<MeshReadResult>(path, [&] {
        MeshReadResult result;
        const gltf::Document document = readDocumentOf(path, result.warnings);
        result.mesh = gltf::mergeScene(document, result.warnings);
        if (const std::string invalid = validateMesh(result.mesh); !invalid.empty())
            fail({}, invalid);
        return result;
    });
}

} // namespace wisp::io
