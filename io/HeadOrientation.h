#pragma once
// Which way an imported head faces, found from its shape; and the size of its skull. Pure
// functions on positions; no Qt, no files. io/HeadPlacement.h uses them to turn and scale a head.
//
// Mesh files do not say which axis is up (OBJ, PLY, OFF, STL), and tools disagree: scanners and
// 3ds Max write +Z up, CT2Hair's heads are +X up, most others +Y. Wisp is +Y up with the face
// toward +Z. Only the six axis directions are considered (files are written in some tool's axes,
// not at odd angles), and a head is recognised by three facts in this order:
//   1. it is mirror-symmetric left to right: the axis whose mirror image of the vertices lies
//      nearest the vertices themselves is the left-right axis;
//   2. the nose is the narrowest extreme: of the four remaining axis directions, the one whose
//      outermost slab (4% of the head's width deep) is narrowest from left to right points the
//      way the face looks (the top of the skull, the back of the head and the neck or the bust
//      all end in a wide slab);
//   3. the skull is above the nose: just above the nose tip the head's cross-section (width times
//      depth) is larger than just below it, where the jaw and the neck are.
// Each fact must hold clearly (the ratios are in HeadOrientation.cpp); when one does not (a box,
// a sphere, a head without a face), the file's own axes are kept and `reason` says why.
//
// Thread safety: pure functions, callable from any thread.

#include <glm/vec3.hpp>

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace wisp::io {

enum class Axis : std::uint8_t { PosX, NegX, PosY, NegY, PosZ, NegZ };

glm::vec3 axisVector(Axis axis);
const char* axisName(Axis axis); // "+X", "-Z", ...
// "+x", "x", "-Z" and the like; nullopt for anything else.
std::optional<Axis> parseAxis(std::string_view text);

// The file axis that comes out as Wisp's +Z when `up` is turned to +Y by the smallest turn (no
// turn about the up axis): +Y up -> +Z, +Z up -> -Y (the usual Z-up to Y-up turn), and so on.
Axis defaultFront(Axis up);

// The point in Wisp's axes: the file's `up` becomes +Y and `front` (perpendicular to `up`)
// becomes +Z; a proper rotation, so triangle winding is kept.
glm::vec3 orient(const glm::vec3& p, Axis up, Axis front);

struct HeadOrientation {
    Axis up = Axis::PosY;
    Axis front = Axis::PosZ;
    bool found = false; // false: the file's axes were kept (up +Y, front +Z)
    std::string reason; // how it was found, or why not
};

HeadOrientation detectHeadOrientation(std::span<const glm::vec3> positions);

// The skull's width in the units of `upright` (positions already +Y up, left-right along X): the
// widest left-to-right extent of the band below the top of the head as deep as it is wide (the
// smallest depth d with width(d) <= d). The band takes in the cranium, and the ears where they
// stick out, but not the shoulders of a bust, which lie further below the top than the head is
// wide. 0 for fewer than one point.
float skullWidth(std::span<const glm::vec3> upright);

} // namespace wisp::io
