#pragma once
// Reads a head (or any collider) mesh from OBJ, PLY, OFF, STL or glTF 2.0 into a TriangleMesh.
//
// Which code reads what, and why:
//   .obj, .stl  OpenMesh's readers, feeding our own importer (not an OpenMesh mesh). OpenMesh's
//               mesh kernels refuse or split non-manifold faces ("complex edge") and drop faces
//               with bad indices with only a line on std::cerr; a head from a scan or a sculpt
//               often has such faces, and grooming wants every triangle with its original
//               vertex numbering. Before OpenMesh runs, a quick scan of the file checks what
//               OpenMesh would silently get wrong (a vertex line that is not three finite
//               numbers shifts every later index; a face index out of range; a binary STL cut
//               short), so those become errors with a line or byte number.
//   .ply        our own reader: ASCII and binary (both endians), `vertex` with x, y, z of any
//               numeric type and any extra properties in any order, `face` and `tristrips`
//               (strips split at -1, alternating winding) lists. OpenMesh cannot read
//               `tristrips`, and its PLY and OFF readers trust the counts in the header, so a
//               corrupt count can allocate gigabytes or loop for minutes.
//   .off        our own reader (ASCII OFF, with optional ST/C/N per-vertex data ignored), for
//               the same reason; binary OFF and 4D OFF are refused with a message.
//   .gltf, .glb io/GltfReader (tinygltf, behind our own checks of the container, the JSON and
//               every accessor): all triangle primitives of the default scene, node transforms
//               applied, merged into one mesh. See GltfReader.h.
// The extension picks the format, case-insensitively; the contents are not sniffed (except
// that a binary glTF misnamed .gltf is recognised by its 'glTF' magic).
//
// Polygons are triangulated as fans from their first corner (fine for the convex polygons
// modellers export; a concave polygon may fold). Triangles that repeat a vertex are dropped.
// Coordinates come back exactly as stored: no unit scaling, no axis change, no vertex welding
// (except STL, whose triangles carry no indices: OpenMesh merges bit-identical corners; and
// glTF, which splits vertices at every normal or UV seam: bit-identical corners are merged).
//
// Thread safety: readMesh may be called from any thread. OpenMesh's readers and its error
// stream are process-wide, so calls that go through OpenMesh are serialised by a mutex.

#include "io/IoError.h"
#include "sim/TriangleMesh.h"

#include <string>
#include <vector>

namespace wisp::io {

struct MeshReadResult {
    TriangleMesh mesh;
    // What the reader skipped or repaired but the artist may want to know: faces with fewer
    // than three distinct corners, point and line elements, PLY elements that are not surfaces,
    // remarks OpenMesh printed (a missing .mtl). Empty for a clean file. Never fatal.
    std::vector<std::string> warnings;
};

// Reads the mesh at `path`. On failure the IoError names the file, the place in it when known
// ("line 12", "byte 1024") and the problem; nothing is printed to std::cerr.
Result<MeshReadResult> readMesh(const std::string& path);

// Lower-case extensions without the dot, in the order a file dialog should offer them.
const std::vector<std::string>& supportedMeshExtensions();

} // namespace wisp::io
