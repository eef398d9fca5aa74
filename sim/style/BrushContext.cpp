#include "sim/style/BrushContext.h"

#include "sim/solver/HairSimulation.h"
#include "sim/style/StrandPicking.h"

#include <glm/geometric.hpp>

#include <algorithm>

namespace wisp {

namespace {
constexpr float kFarMetres = 1.0e4f; // a ray that meets no head
} // namespace

std::vector<BrushRay> brushRays(const BrushContext& context, const BrushSample& sample)
{
    float maxDepth = kFarMetres;
    if (context.head)
        if (const auto hit = context.head->hitAlong(sample.eye_ws, sample.direction_ws))
            maxDepth = hit->distanceMetres + context.brush.radiusMetres;
    std::vector<BrushRay> rays{ { sample.eye_ws, sample.direction_ws, maxDepth } };
    if (context.brush.mirrorX) {
        const float plane = context.head ? context.head->mirrorPlaneX() : 0.0f;
        rays.push_back({ mirroredPoint(sample.eye_ws, plane), mirroredDirection(sample.direction_ws), maxDepth });
    }
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
    if (context.head)
        if (const auto hit = context.head->hitAlong(sample.eye_ws, sample.direction_ws))
            aim = hit->point;
    HairDryer dryer;
    dryer.direction = glm::normalize(aim - sample.eye_ws);
    dryer.nozzle = aim - dryer.direction * kDryerDistanceMetres;
    std::vector<HairDryer> dryers{ dryer };
    if (context.brush.mirrorX) {
        const float plane = context.head ? context.head->mirrorPlaneX() : 0.0f;
        dryer.nozzle = mirroredPoint(dryer.nozzle, plane);
        dryer.direction = mirroredDirection(dryer.direction);
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
