#include "io/MeshReader.h"

#include "io/GltfReader.h"
#include "io/ReadFailure.h"
#include "io/RegularFile.h"
#include "io/mesh/FormatReaders.h"

#include <algorithm>
#include <exception>
#include <new>
#include <string>

namespace wisp::io {

namespace {

std::string supportedList()
{
    std::string s;
    for (const std::string& e : supportedMeshExtensions())
        s += (s.empty() ? "." : ", .") + e;
    return "supported mesh formats are " + s;
}

} // namespace

const std::vector<std::string>& supportedMeshExtensions()
{
    // Function-local so that other files' static initialisers may call this safely.
    static const std::vector<std::string> extensions = { "obj", "ply", "off", "stl", "gltf", "glb" };
    return extensions;
}

Result<MeshReadResult> readMesh(const std::string& path)
{
    try {
        const std::string ext = lowerExtension(path);
        if (ext.empty())
            fail({}, "the file name has no extension, so its format is unknown; " + supportedList());
        const std::vector<std::string>& known = supportedMeshExtensions();
        if (std::find(known.begin(), known.end(), ext) == known.end())
            fail({}, "'." + ext + "' files cannot be read as meshes; " + supportedList());
        // glTF reads its own file and the buffers beside it (io/GltfReader.h).
        if (ext == "gltf" || ext == "glb")
            return readGltf(path);

        const std::string bytes = readRegularFileOrFail(path, { kMaxMeshFileBytes, "mesh", false });
        mesh::MeshBuilder builder;
        MeshReadResult result;
        if (ext == "ply")
            mesh::readPly(bytes, builder, result.warnings);
        else if (ext == "off")
            mesh::readOff(bytes, builder);
        else if (ext == "obj")
            mesh::readObj(bytes, builder, result.warnings);
        else
            mesh::readStl(bytes, builder, result.warnings);

        if (builder.skippedFaces > 0)
            result.warnings.push_back(
                "skipped " + plural(builder.skippedFaces, "face", "faces") + " with fewer than 3 distinct corners");
        if (builder.mesh.triangles.empty()) {
            if (builder.mesh.positions.empty())
                fail({}, "the file holds no vertices and no faces");
            fail({},
                "the file has " + plural(builder.mesh.positions.size(), "vertex", "vertices")
                    + " but no triangles; a head mesh needs a surface");
        }
        if (const std::string problem = validateMesh(builder.mesh); !problem.empty())
            fail({}, problem);
        result.mesh = std::move(builder.mesh);
        return result;
    } catch (const ReadFailure& failure) {
        return IoError{ path, failure.location, failure.message };
    } catch (const std::bad_alloc&) {
        return IoError{ path, {}, "not enough memory to read this mesh" };
    } catch (const std::exception& e) {
        return IoError{ path, {}, std::string("unexpected error while reading: ") + e.what() };
    }
}

} // namespace wisp::io
