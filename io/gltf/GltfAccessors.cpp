#include "io/gltf/GltfAccessors.h"

#include "io/ReadFailure.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>

namespace wisp::io::gltf {

namespace {

// An accessor without a bufferView is all zeros (plus sparse values): its count is not bounded
// by any data in the file, so it is bounded here (16.7 million elements).
constexpr std::size_t maxElementsWithoutData = std::size_t{ 1 } << 24;

std::size_t componentBytes(int componentType)
{
    switch (componentType) {
    case component::Byte:
    case component::UnsignedByte:
        return 1;
    case component::Short:
    case component::UnsignedShort:
        return 2;
    case component::UnsignedInt:
    case component::Float:
        return 4;
    default:
        return 0; // INT and DOUBLE are not glTF 2.0 types
    }
}

// One component as a number. Normalized integers map to [0, 1] or [-1, 1] as the spec says;
// plain integers (KHR_mesh_quantization positions, indices) keep their value.
double componentValue(const unsigned char* p, int componentType, bool normalized)
{
    switch (componentType) {
    case component::Byte: {
        std::int8_t v;
        std::memcpy(&v, p, sizeof v);
        return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case component::UnsignedByte: {
        std::uint8_t v;
        std::memcpy(&v, p, sizeof v);
        return normalized ? v / 255.0 : v;
    }
    case component::Short: {
        std::int16_t v;
        std::memcpy(&v, p, sizeof v);
        return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case component::UnsignedShort: {
        std::uint16_t v;
        std::memcpy(&v, p, sizeof v);
        return normalized ? v / 65535.0 : v;
    }
    case component::UnsignedInt: {
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
const unsigned char* checkedElements(const Document& model, int viewIndex, std::size_t byteOffset, std::size_t count,
    std::size_t elementBytes, std::size_t strideBytes, const std::string& location, const std::string& part)
{
    const std::string prefix = part.empty() ? std::string() : part + ": ";
    if (viewIndex < 0 || static_cast<std::size_t>(viewIndex) >= model.bufferViews.size())
        fail(location,
            prefix + "names bufferViews[" + std::to_string(viewIndex) + "], but the file has "
                + plural(model.bufferViews.size(), "bufferView", "bufferViews"));
    const BufferView& view = model.bufferViews[static_cast<std::size_t>(viewIndex)];
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

} // namespace

const char* componentTypeName(int componentType)
{
    switch (componentType) {
    case component::Byte:
        return "signed bytes";
    case component::UnsignedByte:
        return "unsigned bytes";
    case component::Short:
        return "signed shorts";
    case component::UnsignedShort:
        return "unsigned shorts";
    case component::Int:
        return "signed ints (not a glTF 2.0 type)";
    case component::UnsignedInt:
        return "unsigned ints";
    case component::Float:
        return "floats";
    case component::Double:
        return "doubles (not a glTF 2.0 type)";
    default:
        return "an unknown component type";
    }
}

// Reads accessor `index` with sparse substitutions applied. `use` says what it is for
// ("POSITION of meshes[0].primitives[1]"), and names it in errors.
AccessorValues readAccessor(const Document& model, int index, const std::string& use)
{
    if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size())
        fail(use,
            "names accessors[" + std::to_string(index) + "], but the file has "
                + plural(model.accessors.size(), "accessor", "accessors"));
    const Accessor& accessor = model.accessors[static_cast<std::size_t>(index)];
    const std::string location = indexed("accessors", static_cast<std::size_t>(index)) + " (" + use + ")";

    const std::size_t bytesPerComponent = componentBytes(accessor.componentType);
    if (bytesPerComponent == 0)
        fail(location,
            std::string("component type ") + std::to_string(accessor.componentType) + " ("
                + componentTypeName(accessor.componentType) + ") is not a glTF 2.0 component type");
    const int components = componentsOf(accessor.type);
    if (components < 1 || components > 4 || accessor.type.rfind("MAT", 0) == 0)
        fail(location, "type " + accessor.type + " cannot hold positions or indices");
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
        if (indexType != component::UnsignedByte && indexType != component::UnsignedShort
            && indexType != component::UnsignedInt)
            fail(location,
                std::string("sparse.indices are ") + componentTypeName(indexType)
                    + "; they must be unsigned bytes, shorts or ints");
        const auto sparseCount = static_cast<std::size_t>(sparse.count);
        const std::size_t indexBytes = componentBytes(indexType);
        // Sparse indices and values are tightly packed (their bufferViews have no byteStride).
        const unsigned char* indices = checkedElements(model, sparse.indices.bufferView, sparse.indices.byteOffset,
            sparseCount, indexBytes, indexBytes, location, "sparse.indices");
        const unsigned char* values = checkedElements(model, sparse.values.bufferView, sparse.values.byteOffset,
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

} // namespace wisp::io::gltf
