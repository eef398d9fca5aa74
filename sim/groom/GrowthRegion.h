#pragma once
// A growth region (a layer of the scalp): a painted mask saying where its hair grows, and the wisp
// parameters its hair has there. Lee et al. divide the hair area into regions because different
// parts of a hairstyle behave differently; regions may overlap (each grows its own strands).
//
// The region's wisp parameters are the Wisp-group entries of the registry (Parameters.h); the other
// entries of `values` are ignored. Colour is the hair's colour, sRGB 0..1, root to tip.

#include "sim/geometry/HairCurves.h"
#include "sim/groom/RegionWeights.h"
#include "sim/params/Parameters.h"

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace wisp {

struct GrowthRegion {
    std::uint32_t id = 0; // stable identity: seeds the region's roots, survives renames and reordering
    std::string name;
    // One per head vertex, 0..1 (the painted growth map); shared copy-on-write, so copying a
    // region (an undo snapshot) does not copy its weights.
    RegionWeights weights;
    ParameterValues values; // Wisp-group parameters of this region
    glm::vec3 rootColour{ 0.16f, 0.10f, 0.06f };
    glm::vec3 tipColour{ 0.45f, 0.30f, 0.17f };
    bool visible = true; // hidden regions grow no hair (neither drawn nor simulated)
    // Strands brought in from a hair file (cyHair, USC .data), head space, metres: each becomes a
    // wisp of its own whose key hair is the strand itself, rooted at the nearest point of the head;
    // `weights` are then unused (painting does not apply). Null for a painted region.
    std::shared_ptr<const HairCurves> importedStrands;

    bool operator==(const GrowthRegion&) const = default;
};

// The regions that grow hair: the solo'd one alone when `soloId` names a region, else every
// visible one.
std::vector<const GrowthRegion*> growingRegions(const std::vector<GrowthRegion>& regions, std::uint32_t soloId);
constexpr std::uint32_t kNoSolo = 0xffffffffu;

// What the scalp looks like under the hair, one entry per head vertex: rgb the root colour (sRGB)
// of the growing region that grows most there, a its weight (0: bare skin). Regions' weights of
// another count than `vertexCount` (imported strands) are skipped; real grooms tint the skin under
// the hair toward its colour so the parting and the crown do not show as bare skin.
std::vector<glm::vec4> scalpCoverage(
    const std::vector<GrowthRegion>& regions, std::uint32_t soloId, std::size_t vertexCount);

// Empty when usable; otherwise names the region and the problem
// ("region 'Fringe': weight 12 is not a finite number", "region 'Top': clump_degree: 3 is outside -1..1").
[[nodiscard]] std::string validateRegion(const GrowthRegion& region, std::size_t vertexCount);

} // namespace wisp
