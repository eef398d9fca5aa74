// Fuzz target: io::readMesh on OBJ, PLY, OFF and STL, then what the editor builds from the head.
//
// readMesh picks the format by the file's extension, so the input's first byte picks it too:
// '0' (and any byte % 4 == 0) .obj, '1' .ply, '2' .off, '3' .stl; the rest of the input is the
// file. To replay a crash as a file: `tail -c +2 crash-... > head.obj` (or .ply, .off, .stl).
// glTF has its own target (fuzz_gltf).

#include "fuzz/FuzzSupport.h"
#include "io/MeshReader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    if (size < 1)
        return -1; // not worth keeping in the corpus
    static const char* const kNames[] = { "head.obj", "head.ply", "head.off", "head.stl" };
    const std::string path = wisp::fuzz::writeInput(kNames[data[0] % 4], data + 1, size - 1);
    wisp::io::Result<wisp::io::MeshReadResult> read = wisp::io::readMesh(path);
    if (!read)
        return 0;
    // The artist may tick "Z up" for these formats: the turn is part of what the editor does.
    wisp::fuzz::placeAndExerciseHead(std::move(read).value().mesh, (data[0] & 4) != 0);
    return 0;
}
