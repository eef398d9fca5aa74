#include "io/gltf/GltfDocument.h"

#include "io/Base64.h"
#include "io/GltfSchema.h"
#include "io/ReadFailure.h"
#include "io/RegularFile.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace wisp::io::gltf {

namespace {

using Json = nlohmann::json;

// The schema check guarantees the JSON type and range of every key read here; these turn the
// numbers into C++ ones without overflow (an index past INT_MAX stays out of range, not negative).
std::size_t sizeOf(const Json& value)
{
    if (value.is_number_unsigned())
        return static_cast<std::size_t>(
            std::min<std::uint64_t>(value.get<std::uint64_t>(), std::numeric_limits<std::size_t>::max()));
    const double d = value.get<double>();
    if (!(d > 0.0))
        return 0;
    return d >= 1.8e19 ? std::numeric_limits<std::size_t>::max() : static_cast<std::size_t>(d);
}

int indexOf(const Json& value)
{
    const double d = value.get<double>();
    if (d < 0.0)
        return kAbsent;
    return d >= static_cast<double>(std::numeric_limits<int>::max()) ? std::numeric_limits<int>::max()
                                                                     : static_cast<int>(d);
}

std::size_t sizeAt(const Json& object, const char* key, std::size_t fallback = 0)
{
    const auto it = object.find(key);
    return it == object.end() ? fallback : sizeOf(*it);
}

int indexAt(const Json& object, const char* key, int fallback = kAbsent)
{
    const auto it = object.find(key);
    return it == object.end() ? fallback : indexOf(*it);
}

std::vector<double> numbersAt(const Json& object, const char* key)
{
    std::vector<double> out;
    if (const auto it = object.find(key); it != object.end())
        for (const Json& v : *it)
            out.push_back(v.get<double>());
    return out;
}

std::vector<int> indicesAt(const Json& object, const char* key)
{
    std::vector<int> out;
    if (const auto it = object.find(key); it != object.end())
        for (const Json& v : *it)
            out.push_back(indexOf(v));
    return out;
}

const Json& listAt(const Json& root, const char* key)
{
    static const Json empty = Json::array();
    const auto it = root.find(key);
    return it == root.end() ? empty : *it;
}

AttributeMap attributesOf(const Json& object, const std::string& location)
{
    if (!object.is_object())
        fail(location, "must be an object of accessor indices");
    AttributeMap out;
    for (const auto& [name, value] : object.items()) {
        if (!value.is_number() || value.get<double>() < 0.0 || std::floor(value.get<double>()) != value.get<double>())
            fail(location + "." + name, "must be an accessor index");
        out[name] = indexOf(value);
    }
    return out;
}

// The bytes of buffers[i], before the byteLength check.
std::vector<unsigned char> bufferBytes(const Json& buffer, std::size_t i, bool binary, std::string_view glbBin,
    const std::filesystem::path& folder, std::vector<std::string>& warnings)
{
    const std::string location = indexed("buffers", i);
    const auto uri = buffer.find("uri");
    if (uri == buffer.end()) {
        // The spec: in a GLB, the first buffer without a URI is the BIN chunk.
        if (binary && i == 0)
            return { glbBin.begin(), glbBin.end() };
        warnings.push_back(location + " has no uri and is not a GLB's BIN chunk: it holds no data");
        return {};
    }
    const std::string text = uri->get<std::string>();
    if (text.rfind("data:", 0) == 0) {
        const std::size_t comma = text.find(',');
        if (comma == std::string::npos || comma < 7 || text.compare(comma - 7, 7, ";base64") != 0)
            fail(location + ".uri", "a data URI must hold base64 ('data:...;base64,...')");
        std::size_t bad = 0;
        const std::string_view payload = std::string_view(text).substr(comma + 1);
        std::optional<std::vector<std::uint8_t>> decoded = base64Decode(payload, &bad);
        if (!decoded)
            fail(location + ".uri",
                "the data URI is not valid base64 (character " + std::to_string(bad) + " of its data)");
        return { decoded->begin(), decoded->end() };
    }
    // checkGltfSchema already refused URIs that leave the folder or name anything but a regular file.
    const std::filesystem::path file = folder / gltfUriDecoded(text);
    Result<std::string> bytes = readRegularFile(file.string(), { kMaxMeshFileBytes, "glTF buffer", true });
    if (!bytes)
        fail(location + ".uri", "'" + text + "': " + bytes.error().message);
    return { bytes.value().begin(), bytes.value().end() };
}

} // namespace

int componentsOf(const std::string& type)
{
    if (type == "SCALAR")
        return 1;
    if (type == "VEC2")
        return 2;
    if (type == "VEC3")
        return 3;
    if (type == "VEC4")
        return 4;
    if (type == "MAT2")
        return 4;
    if (type == "MAT3")
        return 9;
    if (type == "MAT4")
        return 16;
    return 0;
}

Document readDocument(const Json& root, bool binary, std::string_view glbBin, const std::filesystem::path& folder,
    std::vector<std::string>& warnings)
{
    Document doc;
    const Json& buffers = listAt(root, "buffers");
    for (std::size_t i = 0; i < buffers.size(); ++i) {
        std::vector<unsigned char> data = bufferBytes(buffers[i], i, binary, glbBin, folder, warnings);
        const std::size_t byteLength = sizeAt(buffers[i], "byteLength");
        if (data.size() < byteLength)
            fail(indexed("buffers", i),
                "byteLength is " + std::to_string(byteLength) + " but its data holds only "
                    + plural(data.size(), "byte", "bytes") + ": the file is truncated or wrong");
        // A GLB pads its BIN chunk to 4 bytes; bounds are checked against the declared length.
        data.resize(byteLength);
        doc.buffers.push_back({ std::move(data) });
    }
    for (const Json& v : listAt(root, "bufferViews"))
        doc.bufferViews.push_back(
            { indexAt(v, "buffer"), sizeAt(v, "byteOffset"), sizeAt(v, "byteLength"), sizeAt(v, "byteStride") });
    for (const Json& a : listAt(root, "accessors")) {
        Accessor accessor;
        accessor.bufferView = indexAt(a, "bufferView");
        accessor.byteOffset = sizeAt(a, "byteOffset");
        accessor.componentType = indexAt(a, "componentType", 0);
        accessor.normalized = a.value("normalized", false);
        accessor.count = sizeAt(a, "count");
        accessor.type = a.at("type").get<std::string>();
        if (const auto sparse = a.find("sparse"); sparse != a.end()) {
            const Json& indices = sparse->at("indices");
            const Json& values = sparse->at("values");
            accessor.sparse.isSparse = true;
            accessor.sparse.count = sizeAt(*sparse, "count");
            accessor.sparse.indices = { indexAt(indices, "bufferView"), sizeAt(indices, "byteOffset"),
                indexAt(indices, "componentType", 0) };
            accessor.sparse.values = { indexAt(values, "bufferView"), sizeAt(values, "byteOffset"), 0 };
        }
        doc.accessors.push_back(std::move(accessor));
    }
    const Json& meshes = listAt(root, "meshes");
    for (std::size_t m = 0; m < meshes.size(); ++m) {
        Mesh mesh;
        mesh.weights = numbersAt(meshes[m], "weights");
        const Json& primitives = meshes[m].at("primitives");
        for (std::size_t p = 0; p < primitives.size(); ++p) {
            const std::string location = indexed("meshes", m) + "." + indexed("primitives", p);
            Primitive primitive;
            primitive.attributes = attributesOf(primitives[p].at("attributes"), location + ".attributes");
            primitive.indices = indexAt(primitives[p], "indices");
            primitive.mode = indexAt(primitives[p], "mode", mode::Triangles);
            const Json& targets = listAt(primitives[p], "targets");
            for (std::size_t t = 0; t < targets.size(); ++t)
                primitive.targets.push_back(attributesOf(targets[t], location + "." + indexed("targets", t)));
            mesh.primitives.push_back(std::move(primitive));
        }
        doc.meshes.push_back(std::move(mesh));
    }
    for (const Json& n : listAt(root, "nodes")) {
        Node node;
        node.children = indicesAt(n, "children");
        node.mesh = indexAt(n, "mesh");
        node.skin = indexAt(n, "skin");
        node.matrix = numbersAt(n, "matrix");
        node.translation = numbersAt(n, "translation");
        node.rotation = numbersAt(n, "rotation");
        node.scale = numbersAt(n, "scale");
        node.weights = numbersAt(n, "weights");
        doc.nodes.push_back(std::move(node));
    }
    for (const Json& s : listAt(root, "scenes"))
        doc.scenes.push_back({ indicesAt(s, "nodes") });
    doc.defaultScene = indexAt(root, "scene");
    return doc;
}

} // namespace wisp::io::gltf
