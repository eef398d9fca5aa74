#pragma once
// Every triangle primitive that a node of the default scene instances, with the node's world
// transform applied, merged into one TriangleMesh (see io/GltfReader.h for the rules).

#include "io/gltf/GltfDocument.h"
#include "sim/geometry/TriangleMesh.h"

#include <string>
#include <vector>

namespace wisp::io::gltf {

// Throws io::ReadFailure; remarks (skipped primitives, dropped triangles) go to `warnings`.
TriangleMesh mergeScene(const Document& model, std::vector<std::string>& warnings);

} // namespace wisp::io::gltf
