#pragma once
// Hair out and in: strands read from and written to the formats other hair tools use.
//
//   .hair  cyHair (Cem Yuksel): 128-byte header ("HAIR", strand count, point count, flags,
//          defaults, 88-byte info), then the arrays the flags name. Read and written; Wisp
//          writes the segments and points arrays (flags 0x3) with the info "Wisp" and skips
//          any thickness, transparency and colour arrays it reads (their sizes are checked).
//   .data  USC-HairSalon: int32 strand count, then per strand int32 n and n x 3 float32.
//          Read and written.
//   .obj   polylines: `v x y z` lines and one `l i j k ...` line per strand; the head, when
//          given, follows as a second object of triangles. Read back: every `l` line of two
//          vertices or more is a strand (faces and `p` points are skipped with a warning).
//   .gltf  glTF 2.0 with the buffer embedded as base64, and .glb (binary glTF).
//          The strands are one LINES primitive (an index pair per segment) with POSITION and a
//          custom per-point `_WIDTH` float attribute (metres, tapering linearly from the root
//          width to the tip width along each strand); the head, when given, is a second mesh
//          on its own node. glTF is in metres with +Y up, as Wisp is. Read back through
//          io/GltfReader's checks (readGltfLines): LINES and LINE_STRIP primitives, `_WIDTH` kept.
// Binary formats are little-endian. The extension picks the format, case-insensitively.
//
// Coordinates are kept exactly as stored (no unit scaling, no axis change): a file made in
// centimetres reads as centimetres. Readers check every count against the size of the file
// before they allocate anything for it, so a corrupt or hostile header is refused with a
// message instead of allocating gigabytes. Writers build the whole file in memory and write
// it atomically (io/AtomicFile.h): a failed write leaves the old file, or none, never half of one.
//
// Strands of zero or one point: readers skip them with a warning (some USC files hold
// one-point strands); writers skip empty strands and write one-point strands as they are
// (as a `p` element in OBJ; not part of the glTF LINES).
//
// Thread safety: all functions may be called from any thread; they share no state.

#include "io/IoError.h"
#include "sim/geometry/HairCurves.h"
#include "sim/geometry/TriangleMesh.h"

#include <optional>
#include <string>
#include <vector>

namespace wisp::io {

struct HairReadResult {
    HairCurves strands;
    // What the reader skipped but the artist may want to know (one-point strands, colour
    // arrays, bytes after the data). Empty for a clean file. Never fatal.
    std::vector<std::string> warnings;
    // Per point, metres: glTF `_WIDTH` where the file has it; empty otherwise.
    std::vector<float> widthsMetres;
};

enum class HairFormat { CyHair, UscData, ObjPolylines, Gltf, Glb };

// The format the extension of `path` names (case-insensitive), or nullopt.
std::optional<HairFormat> hairFormatForPath(const std::string& path);

// Reads .hair, .data, .obj, .gltf or .glb strands. On failure the IoError names the file, the place ("byte 3728")
// and the problem; an extension Wisp cannot read gives a message listing the ones it can.
Result<HairReadResult> readHair(const std::string& path);

struct HairExportOptions {
    float rootWidthMetres = 80e-6f; // glTF _WIDTH at each strand's first point
    float tipWidthMetres = 20e-6f; // glTF _WIDTH at each strand's last point
    const TriangleMesh* head = nullptr; // exported beside the strands by .gltf, .glb and .obj
};

// Writes `strands` in the format the extension of `path` names. Returns success, or what went
// wrong (a missing folder, a strand cyHair cannot hold, a non-finite
// point). Nothing is written unless everything can be.
Result<void> writeHair(const std::string& path, const HairCurves& strands, const HairExportOptions& options = {});

// Lower-case extensions without the dot, in the order a file dialog should offer them.
const std::vector<std::string>& hairReadExtensions(); // hair, data, obj, gltf, glb
const std::vector<std::string>& hairWriteExtensions(); // hair, data, obj, gltf, glb

} // namespace wisp::io
