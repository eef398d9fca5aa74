#pragma once
// The parts of a glTF 2.0 document that make geometry, read from the one parsed (and
// schema-checked, io/GltfSchema.h) JSON document, with every buffer's bytes loaded. Nothing else
// parses the JSON or the container again: the accessors (io/gltf/GltfAccessors.h) and the scene
// (io/gltf/SceneMerger.h) read these structs.

#include <nlohmann/json_fwd.hpp>

#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace wisp::io::gltf {

// glTF's numeric codes (glTF 2.0 specification, "accessor.componentType" and "primitive.mode").
namespace component {
inline constexpr int Byte = 5120;
inline constexpr int UnsignedByte = 5121;
inline constexpr int Short = 5122;
inline constexpr int UnsignedShort = 5123;
inline constexpr int Int = 5124; // not a glTF 2.0 type, named in messages
inline constexpr int UnsignedInt = 5125;
inline constexpr int Float = 5126;
inline constexpr int Double = 5130; // not a glTF 2.0 type, named in messages
} // namespace component

namespace mode {
inline constexpr int Points = 0;
inline constexpr int Lines = 1;
inline constexpr int LineStrip = 3;
inline constexpr int Triangles = 4;
inline constexpr int TriangleStrip = 5;
inline constexpr int TriangleFan = 6;
} // namespace mode

namespace target { // bufferView.target
inline constexpr int ArrayBuffer = 34962;
inline constexpr int ElementArrayBuffer = 34963;
} // namespace target

inline constexpr int kAbsent = -1; // an optional index the file leaves out

struct Buffer {
    std::vector<unsigned char> data; // exactly byteLength bytes
};

struct BufferView {
    int buffer = kAbsent;
    std::size_t byteOffset = 0;
    std::size_t byteLength = 0;
    std::size_t byteStride = 0; // 0: tightly packed
};

struct SparsePart {
    int bufferView = kAbsent;
    std::size_t byteOffset = 0;
    int componentType = 0; // of the indices; the values have the accessor's
};

struct Sparse {
    bool isSparse = false;
    std::size_t count = 0;
    SparsePart indices;
    SparsePart values;
};

struct Accessor {
    int bufferView = kAbsent;
    std::size_t byteOffset = 0;
    int componentType = 0;
    bool normalized = false;
    std::size_t count = 0;
    std::string type; // "SCALAR", "VEC3", ...
    Sparse sparse;
};

using AttributeMap = std::map<std::string, int>; // attribute name -> accessor

struct Primitive {
    AttributeMap attributes;
    int indices = kAbsent;
    int mode = mode::Triangles;
    std::vector<AttributeMap> targets; // morph targets
};

struct Mesh {
    std::vector<Primitive> primitives;
    std::vector<double> weights;
};

struct Node {
    std::vector<int> children;
    int mesh = kAbsent;
    int skin = kAbsent;
    std::vector<double> matrix, translation, rotation, scale, weights; // empty when absent
};

struct Scene {
    std::vector<int> nodes;
};

struct Document {
    std::vector<Buffer> buffers;
    std::vector<BufferView> bufferViews;
    std::vector<Accessor> accessors;
    std::vector<Mesh> meshes;
    std::vector<Node> nodes;
    std::vector<Scene> scenes;
    int defaultScene = kAbsent;
};

// Reads the geometry parts of `root` (already checked by checkGltfSchema) and loads every buffer:
// a data URI is decoded, an external URI is read from `folder` (io/RegularFile rules), and in a
// GLB (`binary`) the buffer without a URI takes the BIN chunk `glbBin`. Throws io::ReadFailure.
Document readDocument(const nlohmann::json& root, bool binary, std::string_view glbBin,
    const std::filesystem::path& folder, std::vector<std::string>& warnings);

// Components per element of an accessor type: SCALAR 1, VEC2 2, VEC3 3, VEC4 4, MAT2 4, MAT3 9,
// MAT4 16; 0 for an unknown type.
int componentsOf(const std::string& type);

// "accessors[3]"
inline std::string indexed(std::string_view array, std::size_t i)
{
    return std::string(array) + "[" + std::to_string(i) + "]";
}

} // namespace wisp::io::gltf
