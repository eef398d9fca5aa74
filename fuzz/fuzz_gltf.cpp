// Fuzz target: io::readGltf (.gltf JSON with data-URI buffers, or a GLB container, recognised by
// its magic whatever the extension), then what the editor builds from the head. The input is the
// file as it is; external buffers resolve in a private temporary folder that holds nothing else.

#include "fuzz/FuzzSupport.h"
#include "io/GltfReader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::string path = wisp::fuzz::writeInput("head.gltf", data, size);
    wisp::io::Result<wisp::io::MeshReadResult> read = wisp::io::readGltf(path);
    if (!read)
        return 0;
    wisp::fuzz::placeAndExerciseHead(std::move(read).value().mesh, false); // glTF is +Y up: no turn
    return 0;
}
