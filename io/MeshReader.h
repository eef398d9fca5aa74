#pragma once
// Reads a head (or any collider) mesh from OBJ, PLY, OFF, STL or glTF 2.0 into a TriangleMesh.
//
// Which code reads what: the file is read once (io/RegularFile) and parsed once, by one reader per
// format under io/mesh/ (PLY ASCII and binary with `face` or `tristrips`; ASCII OFF; OBJ; STL
// binary and ASCII), sharing one tokenizer, byte reader and error type; .gltf and .glb go to
// io/GltfReader. Every count is checked against the bytes that follow it before anything is
// reserved, and every coordinate must be a finite float. No third-party mesh library is used
// (README, "One reader policy": why OpenMesh was dropped).
// The extension picks the format, case-insensitively; the contents are not sniffed (except
// that a binary glTF misnamed .gltf is recognised by its 'glTF' magic).
//
// Polygons are triangulated as fans from their first corner (fine for the convex polygons
// modellers export; a concave polygon may fold). Triangles that repeat a vertex are dropped.
// Coordinates come back exactly as stored: no unit scaling, no axis change, no vertex welding
// (except STL, whose triangles carry no indices, and glTF, which splits vertices at every normal or
// UV seam: corners at equal positions are merged, io/mesh/PositionWelder.h).
//
// Thread safety: readMesh may be called from any thread; it keeps no state between calls.

#include "io/IoError.h"
#include "sim/geometry/TriangleMesh.h"

#include <string>
#include <vector>

namespace wisp::io {

struct MeshReadResult {
    TriangleMesh mesh;
    // What the reader skipped or repaired but the artist may want to know: faces with fewer
    // than three distinct corners, point and line elements, PLY elements that are not surfaces,
    // material libraries named and not opened. Empty for a clean file. Never fatal.
    std::vector<std::string> warnings;
};

// Reads the mesh at `path`. On failure the IoError names the file, the place in it when known
// ("line 12", "byte 1024") and the problem; nothing is printed to std::cerr.
Result<MeshReadResult> readMesh(const std::string& path);

// Lower-case extensions without the dot, in the order a file dialog should offer them.
const std::vector<std::string>& supportedMeshExtensions();

} // namespace wisp::io
