#pragma once
// The pores of a growth region and its wisp sites (Lee et al.: a growth map places pores by pore
// density and wisp size): what of a region's groom does not depend on its painted weights, so
// painting elsewhere never moves a pore or a wisp. Used by Groom.cpp; not part of sim/'s API.

#include "sim/geometry/MeshBvh.h"
#include "sim/geometry/TriangleMesh.h"
#include "sim/groom/Groom.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace wisp::groom_detail {

// Keys of the independent random streams, so that e.g. lengths never correlate with positions.
enum Stream : std::uint64_t { CandidateCount = 1, CandidatePoint, Priority, Keep, LengthJitter, CurlPhase };

struct Pore {
    SurfacePoint surface;
    glm::vec3 position;
    float priority;
};

struct PoreSetStats {
    std::size_t candidates = 0;
    double wantedCandidates = 0.0; // before the cap
    bool capped = false;
};

// What of a region's groom does not depend on its painted weights: the pores, the wisp sites (a
// coarser blue-noise subset, so a wisp's neighbourhood does not shift when an artist paints
// elsewhere) and each pore's nearest site.
struct PoreLayout {
    PoreSetStats stats;
    std::vector<Pore> pores;
    std::vector<std::uint32_t> sites; // pore index of each site
    std::vector<std::uint32_t> siteOfPore; // nearest site of each pore
};

PoreLayout makePoreLayout(const TriangleMesh& head, const GroomSettings& settings, std::size_t maxCandidates);

} // namespace wisp::groom_detail
