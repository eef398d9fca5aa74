#include "sim/geometry/SdfBandRow.h"

#include "sim/geometry/MeshBvh.h" // closestPointOnTriangle: the scalar form, and the degenerate case
#include "sim/geometry/SdfBake.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cstring>

// Compiled once per SIMD target (Google Highway's dynamic dispatch), as the solver's kernels.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "sim/geometry/SdfBandRow.cpp"
#include <hwy/foreach_target.h> // (before highway.h)

#include "sim/solver/SolverLanes-inl.h"

#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace wisp::HWY_NAMESPACE {

namespace {

using lanes::kVectorLanes;
static_assert(sdf_detail::kBandSamplePadding % kVectorLanes == 0, "whole registers in a padded list");
using lanes::select;
using Vec = lanes::Vec;
using VecMask = lanes::VecMask;

struct V3 {
    Vec x, y, z;
};
inline V3 minus(const V3& p, const glm::vec3& a)
{
    return { p.x - a.x, p.y - a.y, p.z - a.z };
}
// glm::dot's order: (x x' + y y') + z z'.
inline Vec dotWith(const glm::vec3& a, const V3& v)
{
    return a.x * v.x + a.y * v.y + a.z * v.z;
}
inline Vec splat(float v)
{
    return Vec{} + v;
}

} // namespace

void bandSamplesOnTarget(const sdf_detail::BakeTriangle& t, const sdf_detail::BandSamples& samples, float* values)
{
    const glm::vec3 a = t.a, b = t.b, c = t.c;
    const glm::vec3 ab = b - a, ac = c - a, bc = c - b;
    for (std::size_t n0 = 0; n0 < samples.count; n0 += kVectorLanes) {
        const int count = static_cast<int>(std::min<std::size_t>(kVectorLanes, samples.count - n0));
        // (The lists are padded to whole registers: the lanes past `count` are computed, not kept.)
        V3 p;
        std::memcpy(&p.x, samples.x + n0, sizeof(Vec));
        std::memcpy(&p.y, samples.y + n0, sizeof(Vec));
        std::memcpy(&p.z, samples.z + n0, sizeof(Vec));
        const V3 ap = minus(p, a), bp = minus(p, b), cp = minus(p, c);
        const Vec d1 = dotWith(ab, ap), d2 = dotWith(ac, ap);
        const Vec d3 = dotWith(ab, bp), d4 = dotWith(ac, bp);
        const Vec d5 = dotWith(ab, cp), d6 = dotWith(ac, cp);
        const Vec vc = d1 * d4 - d3 * d2;
        const Vec vb = d5 * d2 - d1 * d6;
        const Vec va = d3 * d6 - d5 * d4;
        const Vec zero = splat(0.0f);
        // Ericson's regions in closestPointOnTriangle's order: a lane takes the first it is in.
        const VecMask inA = (d1 <= zero) & (d2 <= zero);
        VecMask taken = inA;
        const VecMask inB = ~taken & (d3 >= zero) & (d4 <= d3);
        taken |= inB;
        const VecMask inAB = ~taken & (vc <= zero) & (d1 >= zero) & (d3 <= zero);
        taken |= inAB;
        const VecMask inC = ~taken & (d6 >= zero) & (d5 <= d6);
        taken |= inC;
        const VecMask inAC = ~taken & (vb <= zero) & (d2 >= zero) & (d6 <= zero);
        taken |= inAC;
        const Vec d43 = d4 - d3, d56 = d5 - d6;
        const VecMask inBC = ~taken & (va <= zero) & (d43 >= zero) & (d56 >= zero);
        taken |= inBC;
        const Vec faceDen = va + vb + vc;
        const VecMask inFace = ~taken & (faceDen > zero);
        taken |= inFace;
        // point = (base + s dirS) + t ac, s and t one division each (a zero share adds nothing:
        // x + 0 = x), their numerators and denominators chosen lane by lane.
        const Vec abDen = d1 - d3, acDen = d2 - d6, bcDen = d43 + d56;
        const Vec one = splat(1.0f);
        Vec sNum = zero, sDen = one;
        sNum = select(inAB & (abDen > zero), d1, sNum);
        sDen = select(inAB & (abDen > zero), abDen, sDen);
        sNum = select(inAC & (acDen > zero), d2, sNum);
        sDen = select(inAC & (acDen > zero), acDen, sDen);
        sNum = select(inBC & (bcDen > zero), d43, sNum);
        sDen = select(inBC & (bcDen > zero), bcDen, sDen);
        sNum = select(inFace, vb, sNum);
        sDen = select(inFace, faceDen, sDen);
        const Vec s = sNum / sDen;
        const Vec tFace = select(inFace, vc, zero) / select(inFace, faceDen, one);
        // The base corner (b for b and edge bc, c for c, else a) and the direction s runs along.
        const VecMask fromB = inB | inBC;
        auto pick
            = [&](float av, float bv, float cv) { return select(fromB, splat(bv), select(inC, splat(cv), splat(av))); };
        auto along = [&](float abv, float acv, float bcv) {
            return select(inBC, splat(bcv), select(inAC, splat(acv), splat(abv)));
        };
        Vec qx = pick(a.x, b.x, c.x) + s * along(ab.x, ac.x, bc.x);
        Vec qy = pick(a.y, b.y, c.y) + s * along(ab.y, ac.y, bc.y);
        Vec qz = pick(a.z, b.z, c.z) + s * along(ab.z, ac.z, bc.z);
        qx = select(inFace, qx + tFace * ac.x, qx);
        qy = select(inFace, qy + tFace * ac.y, qy);
        qz = select(inFace, qz + tFace * ac.z, qz);
        const Vec dx = qx - p.x, dy = qy - p.y, dz = qz - p.z;
        const Vec dist2 = dx * dx + dy * dy + dz * dz;
        for (int l = 0; l < count; ++l) {
            float d = dist2[l];
            if (!taken[l]) { // collinear corners: the scalar form's nearest edge
                const glm::vec3 q(p.x[l], p.y[l], p.z[l]);
                const glm::vec3 e = closestPointOnTriangle(q, a, b, c).point - q;
                d = glm::dot(e, e);
            }
            float& out = values[samples.index[n0 + static_cast<std::size_t>(l)]];
            if (d < out)
                out = d;
        }
    }
}

} // namespace wisp::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace wisp::sdf_detail {

HWY_EXPORT(bandSamplesOnTarget);

void bandSamples(const BakeTriangle& triangle, const BandSamples& samples, float* values)
{
    HWY_DYNAMIC_DISPATCH(bandSamplesOnTarget)(triangle, samples, values);
}

} // namespace wisp::sdf_detail
#endif // HWY_ONCE
