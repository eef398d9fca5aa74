#pragma once
// The groom: where strands grow (roots on the head), how they are grouped into wisps, and the rest
// shape each strand returns to. Follows Lee et al., "An Interactive System for 3D Hairstyles":
// a growth map places pores by density, pores are grouped into wisps of `wisp size` strands, each
// wisp has a key hair, and members follow it by clump-degree and clump-rate.

#include "sim/HairCurves.h"
#include "sim/Parameters.h"
#include "sim/TriangleMesh.h"

#include <glm/mat3x3.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace wisp {

class SignedDistanceField;
class MeshBvh;

struct GroomSettings {
    float densityPerCm2 = 0.0f;  // drawn strands per cm² where the growth weight is 1
    int wispSize = 1;            // strands per wisp
    float clumpDegree = 0.0f;    // -1..1
    float clumpRate = 0.0f;      // 0..1, fraction of the strand length where clumping starts
    float lengthMetres = 0.0f;   // arc length
    float lengthVariation = 0.0f;
    int segments = 0;            // per strand; particles = segments + 1
    float curlRadiusMetres = 0.0f;
    float curlTurnsPerMetre = 0.0f;
    std::uint32_t seed = 0;
    float hairOffsetMetres = 0.0f;  // rest shapes keep this far from the skin
};

GroomSettings groomSettingsFrom(const ParameterValues& values);

// Empty when usable; otherwise names the setting and the problem ("segments: 1 is outside 2..127").
std::string validateGroomSettings(const GroomSettings& settings);

struct Groom {
    GroomSettings settings;
    // Per strand (every drawn strand):
    std::vector<SurfacePoint> roots;
    std::vector<glm::vec3> rootPositions;  // head space, metres (the surface points, evaluated)
    std::vector<std::uint32_t> rootIds;  // stable identity of the root in the weight-independent pore set
    std::vector<float> lengths;          // metres
    std::vector<std::uint32_t> wispOf;
    HairCurves rest;  // rest shape of every strand, head space (members built from their key hair)
    // Per wisp:
    std::vector<std::uint32_t> keyStrand;  // the strand that is the wisp's key hair

    std::size_t strandCount() const { return roots.size(); }
    std::size_t wispCount() const { return keyStrand.size(); }
    bool isKey(std::size_t strand) const { return keyStrand[wispOf[strand]] == strand; }
};

struct GroomResult {
    Groom groom;
    std::string error;  // empty on success
    bool ok() const { return error.empty(); }
};

// Places roots where growthWeights (one per vertex, 0..1) allow, groups them into wisps and builds
// rest shapes. Deterministic for a seed, and local: changing the weights in one area adds or removes
// roots only there. If `collider` is given, rest nodes that fall inside the head are pushed out
// (Lee et al. 3.4) so the rest shape drapes over the head.
GroomResult buildGroom(const TriangleMesh& head, std::span<const float> growthWeights, const GroomSettings& settings,
                       const SignedDistanceField* collider = nullptr);

// The first paper's layout: width x height strands of `particlesPerStrand` particles each, rooted on a
// grid over the top of the head (azimuth x polar angle around the head's centre), every strand its
// own wisp so all are simulated.
GroomResult buildGridGroom(const TriangleMesh& head, const MeshBvh& bvh, int width, int height,
                           int particlesPerStrand, float lengthMetres, const SignedDistanceField* collider = nullptr);

// Rebuilds every member strand from its wisp's key hair (level of detail: the keys are simulated,
// members follow). `keyPositions` holds the key strands' points, wisp after wisp, each with the same
// point count as in groom.rest; `headRotation` turns head-space root offsets into world space.
// `out` must have the layout of groom.rest; keys are copied, members written.
void buildMembers(const Groom& groom, std::span<const glm::vec3> keyPositions, const glm::mat3& headRotation,
                  HairCurves& out);

// The key strands' rest shapes, wisp after wisp (the layout buildMembers reads).
HairCurves keyRestCurves(const Groom& groom);

}  // namespace wisp
