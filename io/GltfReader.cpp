#include "io/GltfReader.h"
#include "io/GltfSchema.h"
#include "io/JsonErrors.h"
#include "io/RegularFile.h"

// tinygltf is header-only; its implementation is compiled here and nowhere else. Wisp never
// needs pixels, so no image codec is compiled in (no stb dependency), images referenced by URI
// are not even opened, and TINYGLTF_USE_CPP14 avoids std::function in its JSON walk.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#define TINYGLTF_USE_CPP14
#include <tiny_gltf.h>

#include <nlohmann/json.hpp>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <string_view>
#include <system_error>
#include <unordered_map>
#include <utility>
#include <vector>

namespace wisp::io {

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

// glTF stores numbers little-endian; the accessor reader copies them straight into host numbers.
static_assert(std::endian::native == std::endian::little, "the glTF reader assumes a little-endian host");

// ---------------------------------------------------------------------------------------------
// Limits that keep a hostile or corrupt file from taking the machine down. Each is far above
// any head mesh.

// tinygltf's nested-value parser (extras, extensions) recurses once per level; a file nested
// thousands deep would overflow the stack of a worker thread. Real glTF nests about 8 deep.
constexpr std::size_t maxJsonDepth = 128;
// An accessor without a bufferView is all zeros (plus sparse values): its count is not bounded
// by any data in the file, so it is bounded here (16.7 million elements).
constexpr std::size_t maxElementsWithoutData = std::size_t{1} << 24;
// Many nodes can instance one big mesh; the merged mesh must still fit in memory (~1.2 GB).
constexpr std::size_t maxTriangles = 50'000'000;

// ---------------------------------------------------------------------------------------------
// Failure inside this file: thrown where the problem is found and turned into an IoError by
// readGltf, as in MeshReader.cpp.
struct ReadFailure {
    std::string location;
    std::string message;
};

[[noreturn]] void fail(std::string location, std::string message)
{
    throw ReadFailure{std::move(location), std::move(message)};
}

std::string lowerExtension(const std::string& path)
{
    std::string ext = fs::path(path).extension().string();
    std::transform(
        ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

std::string byteAt(std::uint64_t offset)
{
    return "byte " + std::to_string(offset);
}

std::string indexed(std::string_view array, std::size_t i)
{
    return std::string(array) + "[" + std::to_string(i) + "]";
}

std::string plural(std::size_t n, const char* one, const char* many)
{
    return std::to_string(n) + " " + (n == 1 ? one : many);
}

// tinygltf's messages can quote a whole data URI (megabytes of base64); keep each short.
std::string shortened(std::string text, std::size_t maxChars = 200)
{
    if (text.size() > maxChars)
        text = text.substr(0, maxChars) + "...";
    return text;
}

// tinygltf separates its messages with newlines; an IoError is one line.
std::vector<std::string> messageLines(const std::string& text)
{
    std::vector<std::string> lines;
    std::size_t start = 0;
    while (start < text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string::npos)
            end = text.size();
        std::string line = text.substr(start, end - start);
        while (!line.empty() && (line.back() == '\r' || line.back() == ' '))
            line.pop_back();
        if (!line.empty())
            lines.push_back(shortened(std::move(line)));
        start = end + 1;
    }
    return lines;
}

// ---------------------------------------------------------------------------------------------
// Files: the glTF itself and its external buffers. Only regular files are read: a pipe or a
// device named by a buffer URI would block or never end.

// The whole file, or empty with `problem` set.
std::string readGltfFile(const std::string& path, std::string& problem)
{
    Result<std::string> file = readRegularFile(path, {kMaxMeshFileBytes, "glTF", false});
    if (!file) {
        problem = file.error().message;
        return {};
    }
    return std::move(file).value();
}

// tinygltf's file-system callbacks. It looks for an external buffer first in the glTF's folder
// and then in "." (the working directory); only the first is meant, so only absolute paths (we
// pass the folder as an absolute path) are said to exist.
bool externalFileExists(const std::string& path, void* folder)
{
    // The schema check already refused URIs that leave the folder; this is the second lock.
    return fs::path(path).is_absolute() && folder != nullptr
        && regularFileInside(path, *static_cast<const fs::path*>(folder));
}

std::string externalPathAsIs(const std::string& path, void*)
{
    return path;
}

bool readExternalFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* folder)
{
    if (folder == nullptr || !regularFileInside(path, *static_cast<const fs::path*>(folder))) {
        if (err != nullptr)
            *err += "'" + path + "' is not a regular file inside the glTF file's folder";
        return false;
    }
    std::string problem;
    const std::string bytes = readGltfFile(path, problem);
    if (!problem.empty()) {
        if (err != nullptr)
            *err += problem;
        return false;
    }
    out->assign(bytes.begin(), bytes.end());
    return true;
}

bool refuseWrite(std::string* err, const std::string&, const std::vector<unsigned char>&, void*)
{
    if (err != nullptr)
        *err += "the glTF reader does not write files";
    return false;
}

// Wisp uses no textures: images are accepted and left undecoded.
bool ignoreImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*)
{
    return true;
}

// ---------------------------------------------------------------------------------------------
// The GLB container: a 12-byte header (magic 'glTF', version 2, total length) and chunks of
// (length, type, data). The first chunk is JSON; an optional BIN chunk follows it directly;
// chunks of other types are skipped, as the spec asks.

constexpr std::uint32_t glbMagic = 0x46546C67; // "glTF"
constexpr std::uint32_t glbChunkJson = 0x4E4F534A; // "JSON"
constexpr std::uint32_t glbChunkBin = 0x004E4942; // "BIN\0"

std::uint32_t u32At(std::string_view bytes, std::size_t offset)
{
    std::uint32_t value = 0;
    std::memcpy(&value, bytes.data() + offset, sizeof value);
    return value;
}

std::string chunkTypeName(std::uint32_t type)
{
    std::string name;
    for (int i = 0; i < 4; ++i) {
        const auto c = static_cast<unsigned char>((type >> (8 * i)) & 0xFFu);
        if (c == 0)
            continue;
        if (c < 0x20 || c > 0x7E) {
            char hex[16];
            std::snprintf(hex, sizeof hex, "0x%08X", static_cast<unsigned>(type));
            return hex;
        }
        name += static_cast<char>(c);
    }
    return "'" + name + "'";
}

struct GlbParts {
    std::string_view json;
    std::size_t jsonOffset = 0; // bytes from the start of the file to the JSON text
    std::string_view bin; // empty when the file has no BIN chunk
};

GlbParts splitGlb(std::string_view bytes, std::vector<std::string>& warnings)
{
    if (bytes.size() < 12)
        fail({},
            "the file is " + plural(bytes.size(), "byte", "bytes")
                + ", too short for the 12-byte header of a binary glTF (GLB) file");
    if (u32At(bytes, 0) != glbMagic) {
        const std::size_t first = bytes.find_first_not_of(" \t\r\n");
        const bool looksLikeJson = first != std::string_view::npos && bytes[first] == '{';
        fail(byteAt(0),
            std::string("this is not a binary glTF (GLB) file: it does not start with 'glTF'")
                + (looksLikeJson ? " (it looks like a text glTF: name it .gltf)" : ""));
    }
    const std::uint32_t version = u32At(bytes, 4);
    if (version != 2)
        fail(byteAt(4),
            "GLB version " + std::to_string(version) + "; Wisp reads version 2 (glTF 2.0)"
                + (version == 1 ? ": re-export the head as glTF 2.0" : ""));
    const std::uint32_t length = u32At(bytes, 8);
    if (length < 20)
        fail(byteAt(8),
            "the header declares a total length of " + std::to_string(length)
                + " bytes, too small for the header and a JSON chunk (20 bytes at least)");
    if (length > bytes.size())
        fail(byteAt(8),
            "the header declares " + std::to_string(length) + " bytes but the file has only "
                + std::to_string(bytes.size()) + ": it is truncated");
    if (length < bytes.size())
        warnings.push_back("ignored " + plural(bytes.size() - length, "byte", "bytes")
            + " after the end of the GLB data (the header declares " + std::to_string(length) + ")");

    GlbParts parts;
    bool haveJson = false;
    bool haveBin = false;
    std::size_t chunkIndex = 0;
    std::size_t offset = 12;
    while (offset < length) {
        const std::size_t left = length - offset;
        if (left < 8)
            fail(byteAt(offset), "the data ends inside a chunk header (" + std::to_string(left) + " of 8 bytes)");
        const std::uint32_t chunkBytes = u32At(bytes, offset);
        const std::uint32_t type = u32At(bytes, offset + 4);
        if (chunkBytes > left - 8)
            fail(byteAt(offset),
                "a chunk of " + std::to_string(chunkBytes) + " bytes starts here, but only " + std::to_string(left - 8)
                    + " bytes of GLB data follow its header: it is truncated or corrupt");
        // The spec: chunks start and end on 4-byte boundaries (Khronos' validator:
        // CHUNK_LENGTH_UNALIGNED). A reader that accepts an unaligned length reads the next
        // chunk's header from the wrong bytes.
        if (chunkBytes % 4 != 0)
            fail(byteAt(offset),
                "a chunk of " + std::to_string(chunkBytes)
                    + " bytes: GLB chunk lengths are multiples of 4 (the chunk is not padded; the file is malformed)");
        const std::string_view data = bytes.substr(offset + 8, chunkBytes);
        if (chunkIndex == 0 && type != glbChunkJson)
            fail(byteAt(offset + 4), "the first chunk must be JSON but is of type " + chunkTypeName(type));
        if (type == glbChunkJson) {
            if (haveJson)
                fail(byteAt(offset), "a second JSON chunk; a GLB file holds exactly one");
            if (chunkBytes == 0)
                fail(byteAt(offset), "the JSON chunk is empty");
            parts.json = data;
            parts.jsonOffset = offset + 8;
            haveJson = true;
        } else if (type == glbChunkBin) {
            if (haveBin)
                fail(byteAt(offset), "a second BIN chunk; a GLB file holds at most one");
            if (chunkIndex != 1)
                fail(byteAt(offset),
                    "the BIN chunk must directly follow the JSON chunk, but it is chunk "
                        + std::to_string(chunkIndex + 1));
            parts.bin = data;
            haveBin = true;
        } else {
            warnings.push_back(
                "skipped a GLB chunk of unknown type " + chunkTypeName(type) + " at byte " + std::to_string(offset));
        }
        offset += 8 + std::size_t{chunkBytes};
        ++chunkIndex;
    }
    return parts;
}

void appendU32(std::string& out, std::uint32_t value)
{
    char le[4];
    std::memcpy(le, &value, sizeof le);
    out.append(le, sizeof le);
}

// A GLB that tinygltf reads without surprises: JSON padded with spaces and BIN padded with zeros
// to 4 bytes (tinygltf refuses unaligned chunks), nothing else, lengths exact.
std::string canonicalGlb(const std::string& json, std::string_view bin)
{
    const std::size_t jsonPadded = (json.size() + 3) / 4 * 4;
    const std::size_t binPadded = (bin.size() + 3) / 4 * 4;
    const std::uint64_t total
        = 12 + 8 + std::uint64_t{jsonPadded} + (bin.empty() ? 0 : 8 + std::uint64_t{binPadded});
    if (total > std::numeric_limits<std::uint32_t>::max())
        fail({}, "the glTF data is larger than 4 GiB, more than glTF readers accept");
    std::string glb;
    glb.reserve(static_cast<std::size_t>(total));
    appendU32(glb, glbMagic);
    appendU32(glb, 2);
    appendU32(glb, static_cast<std::uint32_t>(total));
    appendU32(glb, static_cast<std::uint32_t>(jsonPadded));
    appendU32(glb, glbChunkJson);
    glb += json;
    glb.append(jsonPadded - json.size(), ' ');
    if (!bin.empty()) {
        appendU32(glb, static_cast<std::uint32_t>(binPadded));
        appendU32(glb, glbChunkBin);
        glb.append(bin.data(), bin.size());
        glb.append(binPadded - bin.size(), '\0');
    }
    return glb;
}

// ---------------------------------------------------------------------------------------------
// The JSON, checked before tinygltf sees it.

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

// Parses and checks the JSON, and returns it reduced to the parts that make geometry, as text
// for tinygltf.
std::string geometryJson(std::string_view text, bool binary, std::size_t jsonOffset, const fs::path& folder,
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

    static const char* const kept[] = {"asset",       "extensionsUsed", "extensionsRequired", "buffers", "bufferViews",
                                       "accessors",   "meshes",         "nodes",              "scenes",  "scene"};
    Json geometry = Json::object();
    for (const char* key : kept)
        if (auto it = root.find(key); it != root.end())
            geometry[key] = std::move(*it);
    // The parser rejected invalid UTF-8, so nothing needs replacing; `replace` only guarantees
    // that dump() cannot throw.
    return geometry.dump(-1, ' ', false, Json::error_handler_t::replace);
}

// ---------------------------------------------------------------------------------------------
// Accessors, read with every offset checked. tinygltf parses accessors but leaves the reading,
// and so the bounds, to its caller.

std::size_t componentBytes(int componentType)
{
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
        return 4;
    default:
        return 0; // INT and DOUBLE are not glTF 2.0 types
    }
}

const char* componentTypeName(int componentType)
{
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
        return "signed bytes";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return "unsigned bytes";
    case TINYGLTF_COMPONENT_TYPE_SHORT:
        return "signed shorts";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        return "unsigned shorts";
    case TINYGLTF_COMPONENT_TYPE_INT:
        return "signed ints (not a glTF 2.0 type)";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        return "unsigned ints";
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
        return "floats";
    case TINYGLTF_COMPONENT_TYPE_DOUBLE:
        return "doubles (not a glTF 2.0 type)";
    default:
        return "an unknown component type";
    }
}

const char* typeName(int type)
{
    switch (type) {
    case TINYGLTF_TYPE_SCALAR:
        return "SCALAR";
    case TINYGLTF_TYPE_VEC2:
        return "VEC2";
    case TINYGLTF_TYPE_VEC3:
        return "VEC3";
    case TINYGLTF_TYPE_VEC4:
        return "VEC4";
    case TINYGLTF_TYPE_MAT2:
        return "MAT2";
    case TINYGLTF_TYPE_MAT3:
        return "MAT3";
    case TINYGLTF_TYPE_MAT4:
        return "MAT4";
    default:
        return "an unknown type";
    }
}

// One component as a number. Normalized integers map to [0, 1] or [-1, 1] as the spec says;
// plain integers (KHR_mesh_quantization positions, indices) keep their value.
double componentValue(const unsigned char* p, int componentType, bool normalized)
{
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
        std::int8_t v;
        std::memcpy(&v, p, sizeof v);
        return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
        std::uint8_t v;
        std::memcpy(&v, p, sizeof v);
        return normalized ? v / 255.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
        std::int16_t v;
        std::memcpy(&v, p, sizeof v);
        return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        std::uint16_t v;
        std::memcpy(&v, p, sizeof v);
        return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
        std::uint32_t v;
        std::memcpy(&v, p, sizeof v);
        return normalized ? v / 4294967295.0 : v;
    }
    default: {
        float v;
        std::memcpy(&v, p, sizeof v);
        return v;
    }
    }
}

// `count` elements of `elementBytes`, `strideBytes` apart, from `byteOffset` into a bufferView:
// the address of the first, after checking that the last ends inside the view and the view
// inside its buffer. `location` names the accessor for errors, and `part` its sparse part
// ("sparse.indices"), or is empty for the accessor's own elements.
const unsigned char* checkedElements(const tinygltf::Model& model, int viewIndex, std::size_t byteOffset,
    std::size_t count, std::size_t elementBytes, std::size_t strideBytes, const std::string& location,
    const std::string& part)
{
    const std::string prefix = part.empty() ? std::string() : part + ": ";
    if (viewIndex < 0 || static_cast<std::size_t>(viewIndex) >= model.bufferViews.size())
        fail(location,
            prefix + "names bufferViews[" + std::to_string(viewIndex) + "], but the file has "
                + plural(model.bufferViews.size(), "bufferView", "bufferViews"));
    const tinygltf::BufferView& view = model.bufferViews[static_cast<std::size_t>(viewIndex)];
    const std::string viewName = indexed("bufferViews", static_cast<std::size_t>(viewIndex));
    if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size())
        fail(location,
            prefix + viewName + " names buffers[" + std::to_string(view.buffer) + "], but the file has "
                + plural(model.buffers.size(), "buffer", "buffers"));
    const std::vector<unsigned char>& buffer = model.buffers[static_cast<std::size_t>(view.buffer)].data;
    if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset)
        fail(location,
            prefix + viewName + " (byteOffset " + std::to_string(view.byteOffset) + ", byteLength "
                + std::to_string(view.byteLength) + ") lies outside buffers[" + std::to_string(view.buffer) + "] ("
                + plural(buffer.size(), "byte", "bytes") + "): the accessor is out of its buffer's bounds");
    if (count == 0)
        return buffer.data() + view.byteOffset;
    // The last element starts at byteOffset + (count - 1) * stride and must end inside the view;
    // written as divisions so that no product can overflow.
    const bool fits = byteOffset <= view.byteLength && elementBytes <= view.byteLength - byteOffset
        && count - 1 <= (view.byteLength - byteOffset - elementBytes) / strideBytes;
    if (!fits) {
        const double needBytes = static_cast<double>(byteOffset)
            + static_cast<double>(count - 1) * static_cast<double>(strideBytes) + static_cast<double>(elementBytes);
        char need[32];
        std::snprintf(need, sizeof need, "%.0f", needBytes);
        fail(location,
            prefix + plural(count, "element", "elements") + " of " + std::to_string(elementBytes) + " bytes, "
                + std::to_string(strideBytes) + " bytes apart from byte " + std::to_string(byteOffset) + ", need "
                + need + " bytes, but " + viewName + " holds " + std::to_string(view.byteLength)
                + ": the accessor is out of its buffer's bounds");
    }
    return buffer.data() + view.byteOffset + byteOffset;
}

struct AccessorValues {
    std::vector<double> values; // count * components, element after element
    std::size_t count = 0;
    int components = 0;
};

// Reads accessor `index` with sparse substitutions applied. `use` says what it is for
// ("POSITION of meshes[0].primitives[1]"), and names it in errors.
AccessorValues readAccessor(const tinygltf::Model& model, int index, const std::string& use)
{
    if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size())
        fail(use,
            "names accessors[" + std::to_string(index) + "], but the file has "
                + plural(model.accessors.size(), "accessor", "accessors"));
    const tinygltf::Accessor& accessor = model.accessors[static_cast<std::size_t>(index)];
    const std::string location = indexed("accessors", static_cast<std::size_t>(index)) + " (" + use + ")";

    const std::size_t bytesPerComponent = componentBytes(accessor.componentType);
    if (bytesPerComponent == 0)
        fail(location,
            std::string("component type ") + std::to_string(accessor.componentType) + " ("
                + componentTypeName(accessor.componentType) + ") is not a glTF 2.0 component type");
    if (accessor.type != TINYGLTF_TYPE_SCALAR && accessor.type != TINYGLTF_TYPE_VEC2
        && accessor.type != TINYGLTF_TYPE_VEC3 && accessor.type != TINYGLTF_TYPE_VEC4)
        fail(location, std::string("type ") + typeName(accessor.type) + " cannot hold positions or indices");
    const int components = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(accessor.type));
    const std::size_t elementBytes = bytesPerComponent * static_cast<std::size_t>(components);

    AccessorValues result;
    result.count = accessor.count;
    result.components = components;

    if (accessor.bufferView < -1)
        fail(location, "bufferView " + std::to_string(accessor.bufferView) + " is not an index");
    if (accessor.bufferView == -1) {
        // The spec: an accessor without a bufferView is zeros, and usually sparse.
        if (accessor.count > maxElementsWithoutData)
            fail(location,
                "has no data (no bufferView) but " + plural(accessor.count, "element", "elements") + ", more than "
                    + std::to_string(maxElementsWithoutData) + " zeros make no sense");
        result.values.assign(accessor.count * static_cast<std::size_t>(components), 0.0);
    } else {
        std::size_t strideBytes = elementBytes;
        if (static_cast<std::size_t>(accessor.bufferView) < model.bufferViews.size()) {
            const std::size_t declared = model.bufferViews[static_cast<std::size_t>(accessor.bufferView)].byteStride;
            if (declared != 0) {
                if (declared < elementBytes)
                    fail(location,
                        "byteStride " + std::to_string(declared) + " of bufferViews["
                            + std::to_string(accessor.bufferView) + "] is smaller than one element ("
                            + std::to_string(elementBytes) + " bytes)");
                strideBytes = declared;
            }
        }
        const unsigned char* first = checkedElements(
            model, accessor.bufferView, accessor.byteOffset, accessor.count, elementBytes, strideBytes, location, "");
        result.values.resize(accessor.count * static_cast<std::size_t>(components));
        for (std::size_t i = 0; i < accessor.count; ++i)
            for (int c = 0; c < components; ++c)
                result.values[i * static_cast<std::size_t>(components) + static_cast<std::size_t>(c)]
                    = componentValue(first + i * strideBytes + static_cast<std::size_t>(c) * bytesPerComponent,
                        accessor.componentType, accessor.normalized);
    }

    if (accessor.sparse.isSparse) {
        const auto& sparse = accessor.sparse;
        if (sparse.count < 1 || static_cast<std::size_t>(sparse.count) > accessor.count)
            fail(location,
                "sparse.count is " + std::to_string(sparse.count) + "; it must be 1 to the accessor's count ("
                    + std::to_string(accessor.count) + ")");
        const int indexType = sparse.indices.componentType;
        if (indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT
            && indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
            fail(location,
                std::string("sparse.indices are ") + componentTypeName(indexType)
                    + "; they must be unsigned bytes, shorts or ints");
        if (sparse.indices.byteOffset < 0 || sparse.values.byteOffset < 0)
            fail(location, "a sparse byteOffset is negative");
        const auto sparseCount = static_cast<std::size_t>(sparse.count);
        const std::size_t indexBytes = componentBytes(indexType);
        // Sparse indices and values are tightly packed (their bufferViews have no byteStride).
        const unsigned char* indices
            = checkedElements(model, sparse.indices.bufferView, static_cast<std::size_t>(sparse.indices.byteOffset),
                sparseCount, indexBytes, indexBytes, location, "sparse.indices");
        const unsigned char* values
            = checkedElements(model, sparse.values.bufferView, static_cast<std::size_t>(sparse.values.byteOffset),
                sparseCount, elementBytes, elementBytes, location, "sparse.values");
        for (std::size_t k = 0; k < sparseCount; ++k) {
            const double target = componentValue(indices + k * indexBytes, indexType, false);
            if (target >= static_cast<double>(accessor.count))
                fail(location,
                    "sparse index " + std::to_string(k) + " is " + std::to_string(static_cast<std::uint64_t>(target))
                        + ", past the accessor's " + plural(accessor.count, "element", "elements"));
            const auto element = static_cast<std::size_t>(target);
            for (int c = 0; c < components; ++c)
                result.values[element * static_cast<std::size_t>(components) + static_cast<std::size_t>(c)]
                    = componentValue(values + k * elementBytes + static_cast<std::size_t>(c) * bytesPerComponent,
                        accessor.componentType, accessor.normalized);
        }
    }
    return result;
}

// ---------------------------------------------------------------------------------------------
// Nodes and primitives into one mesh.

// A node's transform relative to its parent: its matrix, or translation * rotation * scale.
glm::dmat4 localTransform(const tinygltf::Node& node, std::size_t nodeIndex)
{
    const std::string location = indexed("nodes", nodeIndex);
    if (!node.matrix.empty()) {
        if (node.matrix.size() != 16)
            fail(location, "matrix has " + plural(node.matrix.size(), "number", "numbers") + "; a matrix has 16");
        glm::dmat4 m(1.0);
        for (int column = 0; column < 4; ++column) // glTF and GLM both store column after column
            for (int row = 0; row < 4; ++row)
                m[column][row] = node.matrix[static_cast<std::size_t>(column * 4 + row)];
        return m;
    }
    glm::dmat4 m(1.0);
    if (!node.translation.empty()) {
        if (node.translation.size() != 3)
            fail(location, "translation has " + plural(node.translation.size(), "number", "numbers") + "; it needs 3");
        m[3] = glm::dvec4(node.translation[0], node.translation[1], node.translation[2], 1.0);
    }
    if (!node.rotation.empty()) {
        if (node.rotation.size() != 4)
            fail(location,
                "rotation has " + plural(node.rotation.size(), "number", "numbers") + "; a quaternion needs 4");
        double x = node.rotation[0], y = node.rotation[1], z = node.rotation[2], w = node.rotation[3];
        const double norm = std::sqrt(x * x + y * y + z * z + w * w);
        if (!(norm > 1e-12) || !std::isfinite(norm))
            fail(location, "rotation is not a rotation (its quaternion has length " + std::to_string(norm) + ")");
        // Exporters write unit quaternions to float precision; normalise so that rounding does
        // not scale the head.
        x /= norm, y /= norm, z /= norm, w /= norm;
        const glm::dmat3 r(1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w), // column 0
            2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w), // column 1
            2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y)); // column 2
        for (int c = 0; c < 3; ++c)
            m[c] = glm::dvec4(r[c], 0.0);
    }
    if (!node.scale.empty()) {
        if (node.scale.size() != 3)
            fail(location, "scale has " + plural(node.scale.size(), "number", "numbers") + "; it needs 3");
        for (int c = 0; c < 3; ++c)
            m[c] *= node.scale[static_cast<std::size_t>(c)];
    }
    return m;
}

class SceneMerger {
public:
    SceneMerger(const tinygltf::Model& model, std::vector<std::string>& warnings)
        : m_model(model)
        , m_warnings(warnings)
    {
    }

    TriangleMesh take()
    {
        addScene();
        reportSkipped();
        if (m_mesh.triangles.empty())
            fail({}, "no triangles: " + whyNoTriangles());
        return std::move(m_mesh);
    }

private:
    struct Pending {
        int node;
        int parent; // -1 for a root
        glm::dmat4 parentWorld;
    };

    void addScene()
    {
        const std::vector<tinygltf::Scene>& scenes = m_model.scenes;
        std::vector<int> roots;
        std::string rootsLocation;
        if (m_model.defaultScene >= 0) {
            if (static_cast<std::size_t>(m_model.defaultScene) >= scenes.size())
                fail("scene",
                    "the default scene is scenes[" + std::to_string(m_model.defaultScene) + "], but the file has "
                        + plural(scenes.size(), "scene", "scenes"));
            roots = scenes[static_cast<std::size_t>(m_model.defaultScene)].nodes;
            rootsLocation = indexed("scenes", static_cast<std::size_t>(m_model.defaultScene)) + ".nodes";
        } else if (!scenes.empty()) {
            // The spec leaves the choice to the reader when no default scene is named.
            if (scenes.size() > 1)
                m_warnings.push_back(
                    "the file names no default scene; read scenes[0], the first of " + std::to_string(scenes.size()));
            roots = scenes.front().nodes;
            rootsLocation = "scenes[0].nodes";
        } else {
            // No scenes at all: every node that is nobody's child is a root.
            std::vector<char> isChild(m_model.nodes.size(), 0);
            for (const tinygltf::Node& node : m_model.nodes)
                for (int child : node.children)
                    if (child >= 0 && static_cast<std::size_t>(child) < isChild.size())
                        isChild[static_cast<std::size_t>(child)] = 1;
            for (std::size_t i = 0; i < m_model.nodes.size(); ++i)
                if (!isChild[i])
                    roots.push_back(static_cast<int>(i));
            rootsLocation = "nodes";
        }

        // Iterative, so that a deep (or corrupt) hierarchy cannot overflow the stack. Each node
        // may be reached once: glTF nodes form trees, and a node reached twice (a cycle, or two
        // parents) would loop forever or multiply the mesh.
        std::vector<char> reached(m_model.nodes.size(), 0);
        std::vector<Pending> pending;
        for (auto it = roots.rbegin(); it != roots.rend(); ++it)
            pending.push_back({*it, -1, glm::dmat4(1.0)});
        while (!pending.empty()) {
            const Pending next = pending.back();
            pending.pop_back();
            if (next.node < 0 || static_cast<std::size_t>(next.node) >= m_model.nodes.size())
                fail(next.parent < 0 ? rootsLocation
                                     : indexed("nodes", static_cast<std::size_t>(next.parent)) + ".children",
                    "names nodes[" + std::to_string(next.node) + "], but the file has "
                        + plural(m_model.nodes.size(), "node", "nodes"));
            const auto nodeIndex = static_cast<std::size_t>(next.node);
            if (reached[nodeIndex])
                fail(indexed("nodes", nodeIndex),
                    "is reached twice in the node hierarchy (it has two parents, is listed twice, "
                    "or is its own ancestor); glTF nodes must form trees");
            reached[nodeIndex] = 1;
            const tinygltf::Node& node = m_model.nodes[nodeIndex];
            const glm::dmat4 world = next.parentWorld * localTransform(node, nodeIndex);
            if (node.mesh >= 0) {
                if (static_cast<std::size_t>(node.mesh) >= m_model.meshes.size())
                    fail(indexed("nodes", nodeIndex),
                        "names meshes[" + std::to_string(node.mesh) + "], but the file has "
                            + plural(m_model.meshes.size(), "mesh", "meshes"));
                // A skinned mesh's vertices are placed by its joints, and the spec says to
                // ignore the transform of the node that holds it; without animation the joints
                // rest in the bind pose, where the vertices already are.
                addMeshInstance(nodeIndex, node.skin >= 0 ? glm::dmat4(1.0) : world);
            }
            for (auto it = node.children.rbegin(); it != node.children.rend(); ++it)
                pending.push_back({*it, next.node, world});
        }
    }

    void addMeshInstance(std::size_t nodeIndex, const glm::dmat4& world)
    {
        ++m_meshInstances;
        const tinygltf::Node& node = m_model.nodes[nodeIndex];
        const auto meshIndex = static_cast<std::size_t>(node.mesh);
        const tinygltf::Mesh& mesh = m_model.meshes[meshIndex];
        // A node may override its mesh's default morph weights.
        const std::vector<double>& weights = node.weights.empty() ? mesh.weights : node.weights;
        // A mirroring transform turns counter-clockwise triangles clockwise; swapping two corners
        // turns them back (the spec asks renderers to do the same).
        const bool mirrored = glm::determinant(glm::dmat3(world)) < 0.0;
        // Output vertex of each POSITION element, per accessor, for this instance: primitives that
        // share an accessor share vertices, and unused elements are not copied.
        std::map<int, std::vector<std::uint32_t>> sharedVertices;
        for (std::size_t p = 0; p < mesh.primitives.size(); ++p)
            addPrimitive(meshIndex, p, nodeIndex, world, mirrored, weights, sharedVertices);
    }

    const std::vector<double>& positionsOf(int accessor, const std::string& use)
    {
        auto it = m_positions.find(accessor);
        if (it != m_positions.end())
            return it->second;
        AccessorValues values = readAccessor(m_model, accessor, use);
        if (values.components != 3)
            fail(indexed("accessors", static_cast<std::size_t>(accessor)) + " (" + use + ")",
                "is " + std::string(typeName(m_model.accessors[static_cast<std::size_t>(accessor)].type))
                    + "; positions are VEC3");
        for (std::size_t i = 0; i < values.values.size(); ++i)
            if (!std::isfinite(values.values[i]))
                fail(indexed("accessors", static_cast<std::size_t>(accessor)) + " (" + use + ")",
                    "element " + std::to_string(i / 3) + " is not a finite number");
        return m_positions.emplace(accessor, std::move(values.values)).first->second;
    }

    void addPrimitive(std::size_t meshIndex, std::size_t primitiveIndex, std::size_t nodeIndex, const glm::dmat4& world,
        bool mirrored, const std::vector<double>& weights, std::map<int, std::vector<std::uint32_t>>& sharedVertices)
    {
        const tinygltf::Primitive& primitive = m_model.meshes[meshIndex].primitives[primitiveIndex];
        const std::string location = indexed("meshes", meshIndex) + "." + indexed("primitives", primitiveIndex);
        const int mode = primitive.mode;
        if (mode >= TINYGLTF_MODE_POINTS && mode <= TINYGLTF_MODE_LINE_STRIP) {
            ++m_pointAndLinePrimitives;
            return;
        }
        if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP
            && mode != TINYGLTF_MODE_TRIANGLE_FAN)
            fail(location, "mode " + std::to_string(mode) + " is not a glTF primitive mode (0 to 6)");
        const auto positionAttribute = primitive.attributes.find("POSITION");
        if (positionAttribute == primitive.attributes.end()) {
            ++m_primitivesWithoutPositions;
            return;
        }
        ++m_trianglePrimitives;

        const int positionAccessor = positionAttribute->second;
        const std::vector<double>* positions = &positionsOf(positionAccessor, "POSITION of " + location);
        const std::size_t vertexCount = positions->size() / 3;

        // Morph targets move the vertices by their default weights; a morphed primitive gets
        // its own vertices.
        std::vector<double> morphed;
        for (std::size_t t = 0; t < primitive.targets.size() && t < weights.size(); ++t) {
            const auto target = primitive.targets[t].find("POSITION");
            if (target == primitive.targets[t].end() || weights[t] == 0.0)
                continue;
            const std::string use = "POSITION of " + location + ".targets[" + std::to_string(t) + "]";
            const std::vector<double>& offsets = positionsOf(target->second, use);
            if (offsets.size() != positions->size())
                fail(location,
                    "morph target " + std::to_string(t) + " moves " + plural(offsets.size() / 3, "vertex", "vertices")
                        + ", but the primitive has " + std::to_string(vertexCount));
            if (morphed.empty())
                morphed = *positions;
            for (std::size_t i = 0; i < morphed.size(); ++i)
                morphed[i] += weights[t] * offsets[i];
        }
        std::vector<std::uint32_t> ownVertices;
        std::vector<std::uint32_t>* outputVertex = &ownVertices;
        if (!morphed.empty())
            positions = &morphed;
        else
            outputVertex = &sharedVertices[positionAccessor];
        if (outputVertex->empty())
            outputVertex->assign(vertexCount, unassigned);

        // Indices, or 0, 1, 2, ... when the primitive has none.
        std::vector<std::uint32_t> indices;
        if (primitive.indices >= 0) {
            const std::string use = "indices of " + location;
            if (static_cast<std::size_t>(primitive.indices) < m_model.accessors.size()) {
                const tinygltf::Accessor& accessor = m_model.accessors[static_cast<std::size_t>(primitive.indices)];
                const int type = accessor.componentType;
                if (type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT
                    && type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
                    fail(indexed("accessors", static_cast<std::size_t>(primitive.indices)) + " (" + use + ")",
                        std::string("indices are ") + componentTypeName(type)
                            + "; they must be unsigned bytes, shorts or ints");
                if (accessor.type != TINYGLTF_TYPE_SCALAR || accessor.normalized)
                    fail(indexed("accessors", static_cast<std::size_t>(primitive.indices)) + " (" + use + ")",
                        "indices must be SCALAR and not normalized");
            }
            const AccessorValues values = readAccessor(m_model, primitive.indices, use);
            indices.resize(values.values.size());
            for (std::size_t i = 0; i < indices.size(); ++i) {
                const double v = values.values[i];
                if (v >= static_cast<double>(vertexCount))
                    fail(location,
                        "index " + std::to_string(i) + " is " + std::to_string(static_cast<std::uint64_t>(v))
                            + ", out of range: the POSITION accessor has " + plural(vertexCount, "vertex", "vertices"));
                indices[i] = static_cast<std::uint32_t>(v);
            }
        } else {
            if (vertexCount > std::numeric_limits<std::uint32_t>::max())
                fail(location, "has more vertices than 32-bit indices can number");
            indices.resize(vertexCount);
            for (std::size_t i = 0; i < vertexCount; ++i)
                indices[i] = static_cast<std::uint32_t>(i);
        }

        const std::size_t n = indices.size();
        // Where a vertex of this primitive lands, as it will be stored; computed once per
        // instance.
        auto landed = [&](std::uint32_t local) -> glm::vec3 {
            const std::uint32_t out = (*outputVertex)[local];
            if (out != unassigned)
                return m_mesh.positions[out];
            const glm::dvec4 p = world
                * glm::dvec4((*positions)[3 * local], (*positions)[3 * local + 1], (*positions)[3 * local + 2], 1.0);
            // + 0.0f turns -0 into +0, so that welding sees one zero.
            const glm::vec3 stored
                = glm::vec3(static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)) + 0.0f;
            if (!std::isfinite(stored.x) || !std::isfinite(stored.y) || !std::isfinite(stored.z))
                fail(indexed("nodes", nodeIndex),
                    "its transform takes vertex " + std::to_string(local) + " of " + location
                        + " beyond the range of numbers (not finite)");
            return stored;
        };
        auto corner = [&](std::uint32_t local, const glm::vec3& at) -> std::uint32_t {
            std::uint32_t& out = (*outputVertex)[local];
            if (out == unassigned)
                out = weld(at);
            return out;
        };
        auto emit = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c, bool reportDegenerate) {
            // Strips repeat a vertex on purpose to join runs; elsewhere a triangle without three
            // distinct corners (by index, or by position once welded) is worth a remark.
            if (a == b || b == c || a == c) {
                if (reportDegenerate)
                    ++m_degenerateTriangles;
                return;
            }
            const glm::vec3 atA = landed(a), atB = landed(b), atC = landed(c);
            if (atA == atB || atB == atC || atA == atC) {
                if (reportDegenerate)
                    ++m_degenerateTriangles;
                return;
            }
            if (m_mesh.triangles.size() >= maxTriangles)
                fail({},
                    "more than " + std::to_string(maxTriangles)
                        + " triangles; a head mesh needs far fewer (decimate it)");
            const std::uint32_t outA = corner(a, atA), outB = corner(b, atB), outC = corner(c, atC);
            m_mesh.triangles.push_back(mirrored ? glm::uvec3(outA, outC, outB) : glm::uvec3(outA, outB, outC));
        };

        if (mode == TINYGLTF_MODE_TRIANGLES) {
            for (std::size_t i = 0; i + 2 < n; i += 3)
                emit(indices[i], indices[i + 1], indices[i + 2], true);
            if (n % 3 != 0)
                ++m_primitivesWithLeftoverIndices;
        } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
            // The spec's strip: triangle i is (i, i + 1 + i % 2, i + 2 - i % 2), so that every
            // other triangle is flipped back to the same winding.
            for (std::size_t i = 0; i + 2 < n; ++i)
                emit(indices[i], indices[i + 1 + i % 2], indices[i + 2 - i % 2], false);
        } else {
            // The spec's fan: triangle i is (i + 1, i + 2, 0).
            for (std::size_t i = 0; i + 2 < n; ++i)
                emit(indices[i + 1], indices[i + 2], indices[0], true);
        }
    }

    // The output vertex at `at`, shared by every corner at bit-identical coordinates.
    std::uint32_t weld(const glm::vec3& at)
    {
        WeldKey key;
        static_assert(sizeof key == 3 * sizeof(float));
        std::memcpy(key.data(), &at.x, sizeof(float));
        std::memcpy(key.data() + 1, &at.y, sizeof(float));
        std::memcpy(key.data() + 2, &at.z, sizeof(float));
        const auto [it, added] = m_welded.try_emplace(key, static_cast<std::uint32_t>(m_mesh.positions.size()));
        if (added) {
            if (m_mesh.positions.size() >= std::numeric_limits<std::uint32_t>::max())
                fail({}, "more vertices than 32-bit indices can number");
            m_mesh.positions.push_back(at);
        }
        return it->second;
    }

    void reportSkipped()
    {
        if (m_pointAndLinePrimitives > 0)
            m_warnings.push_back("skipped " + plural(m_pointAndLinePrimitives, "primitive", "primitives")
                + " of points or lines, which are not a surface");
        if (m_primitivesWithoutPositions > 0)
            m_warnings.push_back("skipped " + plural(m_primitivesWithoutPositions, "primitive", "primitives")
                + " without a POSITION attribute");
        if (m_degenerateTriangles > 0)
            m_warnings.push_back("skipped " + plural(m_degenerateTriangles, "triangle", "triangles")
                + " with fewer than 3 distinct corners");
        if (m_primitivesWithLeftoverIndices > 0)
            m_warnings.push_back("ignored the last one or two indices of "
                + plural(m_primitivesWithLeftoverIndices, "primitive", "primitives")
                + ", which make no whole triangle");
    }

    std::string whyNoTriangles() const
    {
        if (m_model.meshes.empty())
            return "the file holds no meshes";
        if (m_meshInstances == 0)
            return "no node of the scene places any of the file's " + plural(m_model.meshes.size(), "mesh", "meshes");
        if (m_trianglePrimitives == 0 && m_pointAndLinePrimitives > 0)
            return "the scene's meshes hold only points and lines, which are not a surface";
        if (m_trianglePrimitives == 0 && m_primitivesWithoutPositions > 0)
            return "the scene's primitives have no POSITION attribute";
        if (m_degenerateTriangles > 0)
            return "every triangle repeats a vertex";
        return "the scene's triangle primitives are empty";
    }

    static constexpr std::uint32_t unassigned = std::numeric_limits<std::uint32_t>::max();

    using WeldKey = std::array<std::uint32_t, 3>; // the float bits of x, y, z
    struct WeldKeyHash {
        std::size_t operator()(const WeldKey& k) const
        {
            std::uint64_t h = 0x9E3779B97F4A7C15ull;
            for (std::uint32_t v : k)
                h = (h ^ v) * 0x100000001B3ull + (h >> 29);
            return static_cast<std::size_t>(h);
        }
    };

    const tinygltf::Model& m_model;
    std::vector<std::string>& m_warnings;
    TriangleMesh m_mesh;
    std::map<int, std::vector<double>> m_positions; // decoded POSITION accessors, in the file's space
    std::unordered_map<WeldKey, std::uint32_t, WeldKeyHash> m_welded; // output vertex at each position
    std::size_t m_meshInstances = 0;
    std::size_t m_trianglePrimitives = 0;
    std::size_t m_pointAndLinePrimitives = 0;
    std::size_t m_primitivesWithoutPositions = 0;
    std::size_t m_primitivesWithLeftoverIndices = 0;
    std::size_t m_degenerateTriangles = 0;
};

// ---------------------------------------------------------------------------------------------

tinygltf::Model loadWithTinyGltf(const std::string& path, std::string_view bytes, std::vector<std::string>& warnings)
{
    // The magic decides, so that a binary file misnamed .gltf still reads; a .glb without it
    // goes to the container check, which says what is wrong.
    const bool namedGlb = lowerExtension(path) == ".glb";
    const bool binary = namedGlb || (bytes.size() >= 4 && u32At(bytes, 0) == glbMagic);
    std::error_code ec;
    const fs::path folder = fs::absolute(fs::path(path), ec).parent_path();
    std::string loaderInput;
    if (binary) {
        const GlbParts parts = splitGlb(bytes, warnings);
        loaderInput = canonicalGlb(geometryJson(parts.json, true, parts.jsonOffset, folder, warnings), parts.bin);
    } else {
        loaderInput = geometryJson(bytes, false, 0, folder, warnings);
    }
    if (loaderInput.size() > std::numeric_limits<std::uint32_t>::max())
        fail({}, "the glTF data is larger than 4 GiB, more than glTF readers accept");

    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(&ignoreImage, nullptr);
    loader.SetFsCallbacks(
        tinygltf::FsCallbacks{&externalFileExists, &externalPathAsIs, &readExternalFile, &refuseWrite,
            const_cast<fs::path*>(&folder)});
    loader.SetStoreOriginalJSONForExtrasAndExtensions(false);

    const std::string baseDir = folder.string();

    tinygltf::Model model;
    std::string err;
    std::string warn;
    bool ok = false;
    try {
        ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn,
                 reinterpret_cast<const unsigned char*>(loaderInput.data()),
                 static_cast<unsigned int>(loaderInput.size()), baseDir)
                    : loader.LoadASCIIFromString(&model, &err, &warn, loaderInput.data(),
                        static_cast<unsigned int>(loaderInput.size()), baseDir);
    } catch (const std::bad_alloc&) {
        throw;
    } catch (const std::exception& e) {
        fail({}, std::string("tinygltf could not read the file: ") + e.what());
    }
    for (std::string& line : messageLines(warn))
        warnings.push_back("tinygltf: " + line);
    const std::vector<std::string> errors = messageLines(err);
    if (!ok) {
        std::string message;
        for (const std::string& line : errors)
            message += (message.empty() ? "" : "; ") + line;
        fail({}, "tinygltf could not read the file: " + (message.empty() ? std::string("it gave no reason") : message));
    }
    // tinygltf also reports problems it read past (a buffer without a URI) as errors.
    for (const std::string& line : errors)
        warnings.push_back("tinygltf: " + line);
    if (binary && !namedGlb)
        warnings.push_back("this is a binary glTF (GLB) file named .gltf; read it as binary");
    return model;
}

} // namespace

namespace {

// The strands of every LINES and LINE_STRIP primitive, in mesh and primitive order: a LINES
// primitive's index pairs are chained while each segment starts where the last one ended (Wisp's
// writer gives each strand's segments in order), a new strand begins where one does not.
GltfLines readLines(const tinygltf::Model& model, std::vector<std::string>& warnings)
{
    GltfLines out;
    bool widthsEverywhere = true;
    std::size_t lineMeshes = 0;
    for (std::size_t m = 0; m < model.meshes.size(); ++m) {
        bool hasLines = false;
        for (std::size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
            const tinygltf::Primitive& primitive = model.meshes[m].primitives[p];
            const std::string location = indexed("meshes", m) + "." + indexed("primitives", p);
            if (primitive.mode != TINYGLTF_MODE_LINE && primitive.mode != TINYGLTF_MODE_LINE_STRIP)
                continue;
            hasLines = true;
            const auto position = primitive.attributes.find("POSITION");
            if (position == primitive.attributes.end())
                fail(location, "a LINES primitive without POSITION");
            const AccessorValues positions = readAccessor(model, position->second, "POSITION of " + location);
            if (positions.components != 3)
                fail(location, "POSITION is not VEC3");
            for (double v : positions.values)
                if (!std::isfinite(static_cast<float>(v)))
                    fail(location, "a POSITION is not a finite number");
            std::vector<double> widths;
            if (const auto width = primitive.attributes.find("_WIDTH"); width != primitive.attributes.end()) {
                AccessorValues w = readAccessor(model, width->second, "_WIDTH of " + location);
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
            if (primitive.indices >= 0) {
                const AccessorValues values = readAccessor(model, primitive.indices, "indices of " + location);
                indices.reserve(values.values.size());
                for (std::size_t i = 0; i < values.values.size(); ++i) {
                    const double v = values.values[i];
                    if (!(v >= 0.0 && v < static_cast<double>(positions.count)) || std::floor(v) != v)
                        fail(location, "index " + std::to_string(i) + " is out of range: the POSITION accessor has " +
                                           plural(positions.count, "vertex", "vertices"));
                    indices.push_back(static_cast<std::uint32_t>(v));
                }
            } else {
                for (std::size_t i = 0; i < positions.count; ++i)
                    indices.push_back(static_cast<std::uint32_t>(i));
            }
            auto point = [&](std::uint32_t i) {
                out.strands.positions.push_back(glm::vec3(static_cast<float>(positions.values[3 * i]),
                                                          static_cast<float>(positions.values[3 * i + 1]),
                                                          static_cast<float>(positions.values[3 * i + 2])));
                out.widthsMetres.push_back(widths.empty() ? 0.0f : static_cast<float>(widths[i]));
            };
            auto endStrand = [&] {
                if (out.strands.positions.size() > out.strands.offsets.back())
                    out.strands.offsets.push_back(static_cast<std::uint32_t>(out.strands.positions.size()));
            };
            if (primitive.mode == TINYGLTF_MODE_LINE_STRIP) {
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
        lineMeshes += hasLines;
    }
    for (std::size_t n = 0; n < model.nodes.size(); ++n) {
        const tinygltf::Node& node = model.nodes[n];
        if (node.mesh >= 0 && static_cast<std::size_t>(node.mesh) < model.meshes.size() &&
            localTransform(node, n) != glm::dmat4(1.0))
            for (const tinygltf::Primitive& p : model.meshes[static_cast<std::size_t>(node.mesh)].primitives)
                if (p.mode == TINYGLTF_MODE_LINE || p.mode == TINYGLTF_MODE_LINE_STRIP) {
                    warnings.push_back(indexed("nodes", n) + " transforms its lines; strands are read as stored");
                    break;
                }
    }
    if (out.strands.strandCount() == 0)
        fail({}, "no strands: the file has no LINES or LINE_STRIP primitive");
    if (!widthsEverywhere)
        out.widthsMetres.clear();
    (void)lineMeshes;
    return out;
}

} // namespace

Result<GltfLines> readGltfLines(const std::string& path)
{
    try {
        std::string problem;
        const std::string bytes = readGltfFile(path, problem);
        if (!problem.empty())
            fail({}, problem);
        std::vector<std::string> warnings;
        const tinygltf::Model model = loadWithTinyGltf(path, bytes, warnings);
        GltfLines lines = readLines(model, warnings);
        lines.warnings = std::move(warnings);
        return lines;
    } catch (const ReadFailure& failure) {
        return IoError{path, failure.location, failure.message};
    } catch (const std::bad_alloc&) {
        return IoError{path, {}, "not enough memory to read this glTF file"};
    } catch (const std::exception& e) {
        return IoError{path, {}, "unexpected error while reading: " + withoutJsonPrefix(e.what())};
    }
}

Result<MeshReadResult> readGltf(const std::string& path)
{
    try {
        std::string problem;
        const std::string bytes = readGltfFile(path, problem);
        if (!problem.empty())
            fail({}, problem);
        MeshReadResult result;
        const tinygltf::Model model = loadWithTinyGltf(path, bytes, result.warnings);
        result.mesh = SceneMerger(model, result.warnings).take();
        if (const std::string invalid = validateMesh(result.mesh); !invalid.empty())
            fail({}, invalid);
        return result;
    } catch (const ReadFailure& failure) {
        return IoError{path, failure.location, failure.message};
    } catch (const std::bad_alloc&) {
        return IoError{path, {}, "not enough memory to read this glTF file"};
    } catch (const std::exception& e) {
        return IoError{path, {}, "unexpected error while reading: " + withoutJsonPrefix(e.what())};
    }
}

} // namespace wisp::io
