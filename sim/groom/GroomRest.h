#pragma once
// A groom's rest shapes (Lee et al.: key hairs grown from the scalp, draped over the head and curled;
// members built around them), reusing the shapes of wisps a previous groom already built. Used by
// Groom.cpp; not part of sim/'s API.

#include "sim/geometry/TriangleMesh.h"
#include "sim/groom/Groom.h"
#include "sim/style/StyleEdits.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace wisp {

class SignedDistanceField;

namespace groom_detail {

// Everything of a groom the layout of its pores cannot tell: what the head looks like there and
// the rest shapes. Rest shapes of wisps equal to one of `previous` (same region, site, members and
// settings) are copied from it instead of being built again.
struct RestContext {
    const TriangleMesh& head;
    const std::vector<glm::vec3>& normals;
    float partX;
    const SignedDistanceField* collider;
    // Rest shapes that are given, not built (imported strands), by strand index.
    const std::unordered_map<std::uint32_t, std::vector<glm::vec3>>* givenRest = nullptr;
    const StyleEdits* style = nullptr; // salon edits by strand identity
};

// Builds every strand's rest shape into groom.rest; returns how many wisps were copied from
// `previous` (may be null) instead of being built again.
std::size_t buildRest(Groom& groom, const RestContext& context, const Groom* previous);

} // namespace groom_detail
} // namespace wisp
