#pragma once
// Hair as USD text (.usda) for Blender, Houdini, Maya and Unreal: the strands as a `BasisCurves`
// prim (linear, non-periodic) with `curveVertexCounts`, `points` (one time sample per frame, or a
// plain value for a static frame) and per-vertex `widths`; the head as a `Mesh` under an `Xform`
// whose `xformOp:transform` carries the head's motion (one sample per frame). The stage is in
// metres (`metersPerUnit = 1`), +Y up (`upAxis = "Y"`), time codes are frame numbers at
// `timeCodesPerSecond` = the bake's fps.
//
// Layout:   /Wisp (Xform, the default prim)
//             /Wisp/hair (BasisCurves, world space)
//             /Wisp/head (Xform: head to world) /Wisp/head/mesh (Mesh, head space)
//
// Numbers are the shortest decimals that read back as the same float32, so the text is
// deterministic (the same frames give byte-identical files) and exact. Strands of fewer than two
// points are left out (a linear curve needs two). Written atomically (io/AtomicFile.h).
//
// Thread safety: any thread; no shared state.

#include "io/IoError.h"
#include "sim/geometry/TriangleMesh.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace wisp::io {

struct UsdaFrame {
    double timeCode = 1.0; // the frame number
    std::span<const glm::vec3> positions; // world space, metres, in the layout of UsdaScene::offsets
    glm::mat4 headToWorld{ 1.0f };
};

struct UsdaScene {
    std::vector<std::uint32_t> offsets{ 0 }; // strand i owns points offsets[i] .. offsets[i+1]-1
    std::vector<float> widthsMetres; // per point (USD "vertex" interpolation)
    std::vector<UsdaFrame> frames; // at least one, time codes increasing
    bool animated = true; // false: one frame written as plain values (a still)
    double framesPerSecond = 24.0;
    const TriangleMesh* head = nullptr; // head space; null: no head
};

// Widths tapering linearly from each strand's root width to `tipRatio` times it at its tip, per
// point of `offsets`' layout.
std::vector<float> taperedWidths(
    std::span<const std::uint32_t> offsets, std::span<const float> rootWidthOfStrand, float tipRatio);

// Writes `scene` to `path` (any name; the caller picks .usda). success, or what
// was wrong with the scene (a count that does not match, a non-finite point, no frame) or the write.
Result<void> writeUsda(const std::string& path, const UsdaScene& scene);

// The text writeUsda writes (for tests and for callers that stream it elsewhere); empty and `error`
// set when the scene is refused.
std::string usdaText(const UsdaScene& scene, std::string* error);

} // namespace wisp::io
