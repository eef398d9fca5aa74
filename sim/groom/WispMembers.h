#pragma once
// Building a wisp's member hairs from its key hair (Lee et al.: members follow their key, clumping
// toward it by clump-degree from clump-rate on). Shared by the groom's rest shapes (Groom.cpp) and
// the drawn frame's members (buildMembers); not part of sim/'s API.

#include "sim/geometry/HairCurves.h"
#include "sim/groom/Groom.h"

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace wisp::groom_detail {

// Lee et al.: members start to clump at clump-rate along the strand and reach clump-degree at the tip.
float clumpAt(float u, float clumpDegree, float clumpRate);

// The strands of each wisp, in strand order.
std::vector<std::vector<std::uint32_t>> membersOfWisps(const Groom& groom);

// Called on each member after it is built (e.g. to keep its shape out of the head).
using MemberFix = std::function<void(std::uint32_t strand, std::span<glm::vec3> points)>;

// Writes wisp w's key (from `key`) and its members into `out`.
void buildWispMembers(const Groom& groom, std::size_t w, std::span<const std::uint32_t> members,
    std::span<const glm::vec3> key, const glm::mat3& headRotation, HairCurves& out, float wetClump = 0.0f,
    const MemberFix& keepShape = {});

} // namespace wisp::groom_detail
