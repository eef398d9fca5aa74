#pragma once
// The glTF JSON checked against the parts of the glTF 2.0 schema that make geometry, before the
// geometry is read from it (io/gltf/GltfDocument). A reader that ignores keys it does not know and
// treats a value of the wrong JSON type as absent (tinygltf did) reads a bufferView with
// `byteOffet` (a typo) or `"byteOffset": true` from the wrong bytes silently, and the head that
// came out was garbage (degenerate enough to crash the BVH build). Here every object that makes geometry (asset,
// buffers, bufferViews, accessors and their sparse parts, meshes, primitives, nodes, scenes) has each of its schema's
// keys of its JSON type and range, and the required ones present. An unknown key within two edits of a key the object
// lacks (`byteOffet`) is a typo and refused, with the key it meant; other unknown keys (glTF 1.0
// leftovers such as an accessor's byteStride) are warned about, as Khronos' validator does.
// Buffer URIs must name a regular file inside the glTF file's folder (canonical paths, so `..`, an
// absolute path, /proc, /dev and a symlink leading out are all outside).

#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace wisp::io {

struct GltfSchemaProblem {
    std::string keyPath; // "bufferViews[1].byteOffet"
    std::string message; // "unknown key (did you mean 'byteOffset'?)"
};

// `folder` is the glTF file's folder (external buffers are resolved against it); empty for a GLB
// read from memory, whose external URIs are then refused.
std::optional<GltfSchemaProblem> checkGltfSchema(
    const nlohmann::json& root, const std::filesystem::path& folder, std::vector<std::string>& warnings);

// A URI's %XX escapes decoded ("my%20head.bin" -> "my head.bin").
std::string gltfUriDecoded(const std::string& uri);

// True when `path` names a regular file inside `folder` once both are made canonical.
bool regularFileInside(const std::filesystem::path& path, const std::filesystem::path& folder);

} // namespace wisp::io
