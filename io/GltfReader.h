#pragma once
// Reads a head (or any collider) from glTF 2.0: `.gltf` (JSON with base64 data-URI buffers or
// external .bin files next to it) and `.glb` (binary container), into one TriangleMesh.
//
// What is read: every triangle primitive (TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN, strips and
// fans converted to triangles) of every mesh that a node of the default scene instances (scene 0
// when the file names no default scene; every root node when it has no scenes), with the node's
// world transform (matrix or translation/rotation/scale, composed down the hierarchy) applied,
// all merged into one mesh. A transform that mirrors (negative determinant) flips the winding
// back, so triangles stay counter-clockwise seen from outside. Default morph-target weights are
// applied to positions; a skinned mesh is read in its bind pose (the glTF spec says to ignore the
// skinned node's own transform). Corners at bit-identical positions (after the transforms) are
// merged into one vertex: glTF splits a vertex wherever its normal or texture coordinate changes
// (a cube's 8 corners are 24 vertices), Wisp reads neither, and split vertices would give the
// head shading seams and open edges. Only vertices that triangles use are kept. Triangles
// without three distinct corners (by index, or by position once merged) are dropped with a
// warning (strips repeat vertices on purpose to join runs, so their dropped triangles are not
// reported); POINTS and LINES primitives are skipped with a warning. Units and axes come back as stored: glTF is metres
// and +Y up by specification, but many exporters ignore the unit, so io/HeadPlacement decides the scale.
//
// One path, one parse (README, "One reader policy"): the GLB container is split here with every
// length checked against the file (io/gltf/GlbContainer); the JSON is parsed once, so that a
// syntax error names its byte, a required extension Wisp cannot honour (Draco, meshopt) is refused
// by name, and the geometry parts are checked against the schema (io/GltfSchema); the geometry is
// read from that same document (io/gltf/GltfDocument), so a malformed material, image, animation
// or camera cannot stop a head from loading and no image is ever opened; accessors are read with
// every offset, stride, count and index checked against their buffer, sparse accessors applied
// (io/gltf/GltfAccessors); the scene is merged in io/gltf/SceneMerger.
// External buffers are looked up only relative to the .gltf's folder (never the working
// directory) and must be regular files, so a URI naming a pipe cannot block the read.
//
// Errors are io::IoError naming the file, the place ("byte 20", "accessors[3]",
// "meshes[0].primitives[1]", "nodes[7]", "extensionsRequired") and the problem.
//
// Thread safety: readGltf may be called from any thread; it keeps no state between calls.

#include "io/IoError.h"
#include "io/MeshReader.h"
#include "sim/geometry/HairCurves.h"

#include <string>
#include <vector>

namespace wisp::io {

// Reads `path` as glTF 2.0. The binary container (GLB) is recognised by its 'glTF' magic, so a
// binary file named .gltf still reads (with a warning); a .glb without the magic is refused.
Result<MeshReadResult> readGltf(const std::string& path);

// Strands from the LINES and LINE_STRIP primitives of a .gltf or .glb (hair as Wisp and other tools
// write it), with the same container, JSON and accessor checks. A LINES primitive's index pairs
// are chained into one strand while each segment starts where the one before ended. Node
// transforms are not applied (Wisp writes none; a transformed lines node gives a warning).
// `widthsMetres` holds the per-point `_WIDTH` when every lines primitive has one, else is empty.
struct GltfLines {
    HairCurves strands;
    std::vector<float> widthsMetres;
    std::vector<std::string> warnings;
};
Result<GltfLines> readGltfLines(const std::string& path);

} // namespace wisp::io
