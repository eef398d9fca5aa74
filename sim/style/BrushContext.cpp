#include "sim/style/BrushContext.h"

#include "sim/solver/HairSimulation.h"
#include "sim/style/StrandPicking.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include <algorithm>

namespace wisp {

namespace {

constexpr float kFarMetres = 1.0e4f; // a ray that meets no head

// `p_ws` (a point) or `d_ws` (a direction) mirrored across the head's mirror plane, which is
// x = plane in head space.
glm::vec3 mirroredPointWorld(const BrushContext& context, const glm::vec3& p_ws)
{
    const float plane = context.head ? context.head->mirrorPlaneX() : 0.0f;
    const glm::vec3 p_hs = glm::vec3(worldToHeadOf(context.frame) * glm::vec4(p_ws, 1.0f));
    return glm::vec3(headToWorldOf(context.frame) * glm::vec4(mirroredPoint(p_hs, plane), 1.0f));
}

glm::vec3 mirroredDirectionWorld(const BrushContext& context, const glm::vec3& d_ws)
{
    const glm::vec3 d_hs = glm::mat3(worldToHeadOf(context.frame)) * d_ws;
    return glm::mat3(headToWorldOf(context.frame)) * mirroredDirection(d_hs);
}

} // namespace

std::optional<HeadModel::SurfaceHit> headHitAlong(
    const BrushContext& context, const glm::vec3& origin_ws, const glm::vec3& direction_ws)
{
    if (!context.head)
        return std::nullopt;
    const glm::mat4 toHead = worldToHeadOf(context.frame);
    auto hit = context.head->hitAlong(glm::vec3(toHead * glm::vec4(origin_ws, 1.0f)), glm::mat3(toHead) * direction_ws);
    if (hit) { // a rigid transform keeps the distance along the ray
        const glm::mat4 toWorld = headToWorldOf(context.frame);
        hit->point = glm::vec3(toWorld * glm::vec4(hit->point, 1.0f));
        hit->normal = glm::mat3(toWorld) * hit->normal;
    }
    return hit;
}

std::vector<BrushRay> brushRays(const BrushContext& context, const BrushSample& sample)
{
    float maxDepth = kFarMetres;
    if (const auto hit = headHitAlong(context, sample.eye_ws, sample.direction_ws))
        maxDepth = hit->distanceMetres + context.brush.radiusMetres;
    std::vector<BrushRay> rays{ { sample.eye_ws, sample.direction_ws, maxDepth } };
    if (context.brush.mirrorX)
        rays.push_back({ mirroredPointWorld(context, sample.eye_ws),
            mirroredDirectionWorld(context, sample.direction_ws), maxDepth });
    return rays;
}

bool hasStyledHair(const BrushContext& context)
{
    const Frame* frame = context.frame.get();
    return frame && frame->groomShape && frame->groomShape->identities.size() == frame->strands.strandCount();
}

float strandLengthNow(
    const BrushContext& context, const StyleEdits& edits, std::uint64_t identity, std::uint32_t strand)
{
    if (const auto found = edits.find(identity); found != edits.end()) {
        if (!found->second.shape.empty())
            return strandLength(found->second.shape);
        if (found->second.lengthMetres > 0.0f)
            return found->second.lengthMetres;
    }
    const GroomShape* shape = context.frame ? context.frame->groomShape.get() : nullptr;
    return shape && strand < shape->lengths.size() ? shape->lengths[strand] : 0.0f;
}

std::uint32_t heldStrandOf(const BrushContext& context, std::uint32_t strand)
{
    const GroomShape& shape = *context.frame->groomShape;
    if (context.everyStrandSimulated || strand >= shape.wispOf.size())
        return strand;
    return shape.keyOfWisp[shape.wispOf[strand]];
}

std::vector<HairDryer> dryersFor(const BrushContext& context, const BrushSample& sample)
{
    glm::vec3 aim = sample.eye_ws + sample.direction_ws * sample.aimDepthMetres;
    if (const auto hit = headHitAlong(context, sample.eye_ws, sample.direction_ws))
        aim = hit->point;
    HairDryer dryer;
    dryer.direction = glm::normalize(aim - sample.eye_ws);
    dryer.nozzle = aim - dryer.direction * kDryerDistanceMetres;
    std::vector<HairDryer> dryers{ dryer };
    if (context.brush.mirrorX) {
        dryer.nozzle = mirroredPointWorld(context, dryer.nozzle);
        dryer.direction = mirroredDirectionWorld(context, dryer.direction);
        dryers.push_back(dryer);
    }
    return dryers;
}

std::shared_ptr<const GroomShape> groomShapeOf(const HairSimulation& simulation)
{
    auto shape = std::make_shared<GroomShape>();
    const Groom& groom = simulation.groom();
    shape->rest = groom.rest;
    if (simulation.simulatesAllStrands()) {
        for (std::uint32_t i = 0; i < groom.strandCount(); ++i)
            shape->keyStrands.push_back(i);
    } else {
        shape->keyStrands = groom.keyStrand;
    }
    std::sort(shape->keyStrands.begin(), shape->keyStrands.end());
    shape->identities.resize(groom.strandCount());
    for (std::size_t i = 0; i < groom.strandCount(); ++i)
        shape->identities[i] = groom.strandIdentity(i);
    shape->wispOf = groom.wispOf;
    shape->keyOfWisp = groom.keyStrand;
    shape->lengths = groom.lengths;
    return shape;
}

} // namespace wisp
