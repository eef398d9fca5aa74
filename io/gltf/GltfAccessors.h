#pragma once
// Accessors read with every offset, stride, count and sparse index checked against the bufferView
// and buffer it names (glTF 2.0 specification, "Accessors"), sparse substitutions applied.

#include "io/gltf/GltfDocument.h"

#include <cstddef>
#include <string>
#include <vector>

namespace wisp::io::gltf {

struct AccessorValues {
    std::vector<double> values; // count * components, element after element
    std::size_t count = 0;
    int components = 0;
};

// Reads accessor `index`. `use` says what it is for ("POSITION of meshes[0].primitives[1]") and
// names it in errors. Only SCALAR and VEC2..VEC4 accessors are read. Throws io::ReadFailure.
AccessorValues readAccessor(const Document& model, int index, const std::string& use);

// "unsigned shorts", for messages.
const char* componentTypeName(int componentType);

} // namespace wisp::io::gltf
