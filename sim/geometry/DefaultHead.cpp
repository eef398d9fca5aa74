// The mesh must come out bit-identical on every machine, but the build may use -march=native,
// where compilers fuse a * b + c into one FMA on CPUs that have it, rounding differently from
// those that do not. Keep every product rounded on its own in this file (set before the includes
// so the inlined GLM code follows the same rule).
#if defined(__clang__)
#pragma clang fp contract(off)
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

#include "sim/geometry/DefaultHead.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

// The head is a signed distance function (negative inside) built from smooth unions and subtractions
// of ellipsoids and capsules, contoured on a regular grid with surface nets (one vertex per surface
// patch of a cell), pulled onto the exact surface and lightly smoothed. Only +, -, *, / and sqrt go
// into the mesh, all correctly rounded in IEEE arithmetic, so every machine builds the same mesh.

namespace wisp {
namespace {

using glm::vec2;
using glm::vec3;

constexpr float kCell = 0.0038f; // grid spacing: still shows lips and nostrils, ~34k triangles
// At least two cells of air around the head on every side, so the surface closes inside the grid.
const vec3 kGridMin{ -0.105f, -0.235f, -0.125f };
const vec3 kGridMax{ 0.105f, 0.140f, 0.135f };

// --- Signed distance primitives -----------------------------------------------------------------

// First-order ellipsoid distance: not exact away from the surface, but smooth and right at it.
// Inline and written with reciprocals because the radii are constants: the compiler folds 1 / r,
// and the distance costs multiplies instead of six divisions (it is evaluated ~200k times).
inline float ellipsoid(vec3 p, vec3 r)
{
    const vec3 inv = 1.0f / r;
    const float k0 = glm::length(p * inv);
    const float k1 = glm::length(p * (inv * inv));
    return k1 > 0.0f ? k0 * (k0 - 1.0f) / k1 : -std::min(r.x, std::min(r.y, r.z));
}

float ellipse(vec2 p, vec2 r)
{
    const vec2 inv = 1.0f / r;
    const float k0 = glm::length(p * inv);
    const float k1 = glm::length(p * (inv * inv));
    return k1 > 0.0f ? k0 * (k0 - 1.0f) / k1 : -std::min(r.x, r.y);
}

// Capsule whose radius goes from ra at a to rb at b.
float capsule(vec3 p, vec3 a, vec3 b, float ra, float rb)
{
    const vec3 pa = p - a, ba = b - a;
    const float h = glm::clamp(glm::dot(pa, ba) * (1.0f / glm::dot(ba, ba)), 0.0f, 1.0f);
    return glm::length(pa - ba * h) - (ra + (rb - ra) * h);
}

// Polynomial smooth minimum: blends two shapes over a fillet of width k instead of a hard crease.
float smoothMin(float a, float b, float k)
{
    const float h = std::max(k - std::abs(a - b), 0.0f) * (1.0f / k);
    return std::min(a, b) - h * h * k * 0.25f;
}

float smoothSubtract(float from, float cut, float k)
{
    return -smoothMin(-from, cut, k);
}

// The ear, in the frame of the head's right half (x >= 0). Shared with the growth map, which keeps
// hair off it.
float earDistance(vec3 m)
{
    vec3 e = m - vec3(0.072f, -0.004f, -0.012f);
    // Turn the ear out by 20 degrees (its back edge stands off the skull) and tilt it back by 15
    // (top behind the lobe), as real ears sit.
    e = vec3(0.940f * e.x + 0.342f * e.z, e.y, -0.342f * e.x + 0.940f * e.z);
    e = vec3(e.x, 0.966f * e.y + 0.259f * e.z, -0.259f * e.y + 0.966f * e.z);
    float ear = ellipsoid(e, vec3(0.011f, 0.031f, 0.019f));
    // The bowl of the concha, so the ear is a shell rather than a lump.
    ear = smoothSubtract(ear, ellipsoid(e - vec3(0.012f, -0.003f, 0.002f), vec3(0.007f, 0.017f, 0.011f)), 0.004f);
    return ear;
}

float headDistance(vec3 p)
{
    const vec3 m{ std::abs(p.x), p.y, p.z }; // mirrored: paired features are written once

    // Cranium, a little narrower at the forehead than over the parietal bones, with the occipital
    // bulge behind.
    vec3 c = p - vec3(0.0f, 0.022f, -0.010f);
    c.x *= 1.0f + 0.16f * glm::clamp(c.z / 0.091f, 0.0f, 1.0f);
    float d = ellipsoid(c, vec3(0.075f, 0.098f, 0.091f));
    d = smoothMin(d, ellipsoid(p - vec3(0.0f, -0.005f, -0.030f), vec3(0.062f, 0.070f, 0.070f)), 0.02f);
    d = smoothMin(d, ellipsoid(p - vec3(0.0f, 0.038f, -0.018f), vec3(0.071f, 0.075f, 0.082f)), 0.02f); // rounder vault

    // Face mass, jaw line and chin.
    d = smoothMin(d, ellipsoid(p - vec3(0.0f, -0.030f, 0.026f), vec3(0.056f, 0.070f, 0.062f)), 0.03f);
    d = smoothMin(d, capsule(m, vec3(0.044f, -0.068f, -0.018f), vec3(0.014f, -0.095f, 0.062f), 0.010f, 0.013f), 0.035f);
    d = smoothMin(d, ellipsoid(m - vec3(0.042f, -0.045f, 0.008f), vec3(0.015f, 0.032f, 0.030f)), 0.04f); // masseter
    d = smoothMin(d, ellipsoid(p - vec3(0.0f, -0.095f, 0.068f), vec3(0.019f, 0.014f, 0.015f)), 0.015f);

    // Cheekbones and a soft brow ridge.
    d = smoothMin(d, ellipsoid(m - vec3(0.046f, -0.010f, 0.056f), vec3(0.020f, 0.013f, 0.020f)), 0.02f);
    d = smoothMin(d, ellipsoid(m - vec3(0.028f, 0.025f, 0.078f), vec3(0.026f, 0.010f, 0.012f)), 0.025f);
    d = smoothMin(d, ellipsoid(m - vec3(0.036f, -0.045f, 0.046f), vec3(0.020f, 0.025f, 0.025f)), 0.03f); // full cheeks

    // Eye sockets carved under the brow, with the eyeballs sitting in them.
    d = smoothSubtract(d, ellipsoid(m - vec3(0.032f, 0.006f, 0.092f), vec3(0.019f, 0.011f, 0.015f)), 0.01f);
    d = smoothMin(d, glm::length(m - vec3(0.032f, 0.008f, 0.071f)) - 0.013f, 0.005f);

    // Nose: bridge to tip, then the wings around the nostrils.
    d = smoothMin(d, capsule(p, vec3(0.0f, 0.012f, 0.087f), vec3(0.0f, -0.030f, 0.104f), 0.006f, 0.010f), 0.01f);
    d = smoothMin(d, ellipsoid(m - vec3(0.011f, -0.033f, 0.090f), vec3(0.007f, 0.006f, 0.008f)), 0.008f);

    // Lips: two soft rolls whose meeting crease reads as the mouth.
    d = smoothMin(d, ellipsoid(p - vec3(0.0f, -0.053f, 0.087f), vec3(0.023f, 0.006f, 0.007f)), 0.014f);
    d = smoothMin(d, ellipsoid(p - vec3(0.0f, -0.064f, 0.084f), vec3(0.019f, 0.006f, 0.007f)), 0.014f);

    d = smoothMin(d, earDistance(m), 0.006f);

    // Neck: an elliptic column leaning forward, closed flat (with a rounded rim) at the bottom.
    const vec2 neckAxis{ 0.0f, -0.024f - 0.15f * (p.y + 0.05f) };
    float neck = ellipse(vec2(p.x, p.z) - neckAxis, vec2(0.052f, 0.056f));
    neck = smoothSubtract(neck, 0.215f + p.y, 0.01f); // keep y > -0.215
    neck = std::max(neck, p.y); // ends inside the head
    return smoothMin(d, neck, 0.02f);
}

// --- Surface nets -------------------------------------------------------------------------------

// Cube corner c sits at offset (c & 1, c >> 1 & 1, c >> 2 & 1). Edge 4a + u + 2v runs along axis a,
// at offset u along axis (a + 1) % 3 and v along (a + 2) % 3.
struct CubeTables {
    std::array<std::array<int, 2>, 12> edgeCorners{};
    std::array<std::array<int, 4>, 6> faceCorners{}; // cyclic, the same global order from both cells
    std::array<std::array<int, 4>, 6> faceEdges{}; // edge k joins faceCorners k and k + 1
};

int cornerAt(int a, int along, int u, int v)
{
    int offset[3];
    offset[a] = along;
    offset[(a + 1) % 3] = u;
    offset[(a + 2) % 3] = v;
    return offset[0] | offset[1] << 1 | offset[2] << 2;
}

CubeTables makeCubeTables()
{
    CubeTables t;
    for (int a = 0; a < 3; ++a)
        for (int e = 0; e < 4; ++e)
            t.edgeCorners[4 * a + e] = { cornerAt(a, 0, e & 1, e >> 1), cornerAt(a, 1, e & 1, e >> 1) };
    const int cycle[4][2] = { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 } };
    for (int f = 0; f < 6; ++f) {
        const int a = f / 2, side = f % 2;
        for (int k = 0; k < 4; ++k)
            t.faceCorners[f][k] = cornerAt(a, side, cycle[k][0], cycle[k][1]);
        for (int k = 0; k < 4; ++k) {
            const int c0 = t.faceCorners[f][k], c1 = t.faceCorners[f][(k + 1) % 4];
            for (int e = 0; e < 12; ++e)
                if (std::min(t.edgeCorners[e][0], t.edgeCorners[e][1]) == std::min(c0, c1)
                    && std::max(t.edgeCorners[e][0], t.edgeCorners[e][1]) == std::max(c0, c1))
                    t.faceEdges[f][k] = e;
        }
    }
    return t;
}

struct Grid {
    glm::ivec3 n{ 0 };
    std::vector<float> values;
    std::size_t index(int i, int j, int k) const { return (std::size_t(k) * n.y + j) * n.x + i; }
    vec3 position(int i, int j, int k) const { return kGridMin + vec3(float(i), float(j), float(k)) * kCell; }
};

// Samples the distance everywhere, but evaluates it exactly only in 4x4x4 blocks near the surface:
// far blocks only need the right sign, which their centre value gives with a wide margin.
Grid sampleHead()
{
    Grid g;
    g.n = glm::ivec3(glm::floor((kGridMax - kGridMin) / kCell)) + 1;
    g.values.resize(std::size_t(g.n.x) * g.n.y * g.n.z);
    constexpr int kBlock = 4;
    const float farEnough = 2.0f * (kBlock - 1) * kCell * 0.8661f; // twice the block's half-diagonal
    for (int bk = 0; bk < g.n.z; bk += kBlock)
        for (int bj = 0; bj < g.n.y; bj += kBlock)
            for (int bi = 0; bi < g.n.x; bi += kBlock) {
                const glm::ivec3 hi = glm::min(glm::ivec3(bi, bj, bk) + kBlock, g.n);
                const vec3 centre = 0.5f * (g.position(bi, bj, bk) + g.position(hi.x - 1, hi.y - 1, hi.z - 1));
                const float dc = headDistance(centre);
                const bool far = std::abs(dc) > farEnough;
                for (int k = bk; k < hi.z; ++k)
                    for (int j = bj; j < hi.y; ++j)
                        for (int i = bi; i < hi.x; ++i)
                            g.values[g.index(i, j, k)] = far ? dc : headDistance(g.position(i, j, k));
            }
    return g;
}

struct QuadMesh {
    std::vector<vec3> positions;
    std::vector<std::array<std::uint32_t, 4>> quads; // counter-clockwise from outside
};

// Surface nets, with one vertex per connected surface patch of a cell rather than per cell, so
// cells the surface passes through twice do not pinch it into a non-manifold vertex. Patches are
// found by pairing each face's crossed edges; a face crossed four times is resolved by its centre
// value, computed identically from both cells that share it.
QuadMesh contour(const Grid& g)
{
    const CubeTables t = makeCubeTables();
    const glm::ivec3 cells = g.n - 1;
    constexpr std::uint32_t kNone = 0xffffffffu;
    std::vector<std::uint32_t> cellSlot(std::size_t(cells.x) * cells.y * cells.z, kNone);
    std::vector<std::array<std::uint32_t, 12>> edgeVertex; // per surface cell: vertex of each crossed edge
    QuadMesh out;
    auto inside = [](float v) { return v < 0.0f; };

    for (int k = 0; k < cells.z; ++k)
        for (int j = 0; j < cells.y; ++j)
            for (int i = 0; i < cells.x; ++i) {
                float v[8];
                int insideCount = 0;
                for (int c = 0; c < 8; ++c) {
                    v[c] = g.values[g.index(i + (c & 1), j + (c >> 1 & 1), k + (c >> 2 & 1))];
                    insideCount += inside(v[c]);
                }
                if (insideCount == 0 || insideCount == 8)
                    continue;
                int parent[12];
                for (int e = 0; e < 12; ++e)
                    parent[e] = e;
                auto find = [&](int e) {
                    while (parent[e] != e)
                        e = parent[e];
                    return e;
                };
                auto join = [&](int a, int b) { parent[find(a)] = find(b); };
                unsigned crossedMask = 0;
                for (int e = 0; e < 12; ++e)
                    crossedMask |= unsigned(inside(v[t.edgeCorners[e][0]]) != inside(v[t.edgeCorners[e][1]])) << e;
                auto crossed = [&](int e) { return (crossedMask >> e & 1u) != 0; };
                for (int f = 0; f < 6; ++f) {
                    const auto& fe = t.faceEdges[f];
                    const auto& fc = t.faceCorners[f];
                    int hits[4], count = 0;
                    for (int e : fe)
                        if (crossed(e))
                            hits[count++] = e;
                    if (count == 2) {
                        join(hits[0], hits[1]);
                    } else if (count == 4) {
                        // Corners alternate in sign: isolate the two corners whose sign the centre lacks.
                        const bool centreInside = inside(v[fc[0]] + v[fc[1]] + v[fc[2]] + v[fc[3]]);
                        const int isolated = inside(v[fc[0]]) == centreInside ? 1 : 0;
                        join(fe[(isolated + 3) % 4], fe[isolated]);
                        join(fe[(isolated + 1) % 4], fe[(isolated + 2) % 4]);
                    }
                }
                const std::size_t cell = (std::size_t(k) * cells.y + j) * cells.x + i;
                cellSlot[cell] = std::uint32_t(edgeVertex.size());
                auto& slot = edgeVertex.emplace_back();
                slot.fill(kNone);
                // Each patch's vertex starts at the mean of its edge crossings.
                std::uint32_t patchVertex[12];
                int patchCrossings[12] = {};
                for (int e = 0; e < 12; ++e) {
                    if (!crossed(e))
                        continue;
                    const int patch = find(e);
                    if (patchCrossings[patch]++ == 0) {
                        patchVertex[patch] = std::uint32_t(out.positions.size());
                        out.positions.emplace_back(0.0f);
                    }
                    const int c0 = t.edgeCorners[e][0], c1 = t.edgeCorners[e][1];
                    const vec3 p0 = g.position(i + (c0 & 1), j + (c0 >> 1 & 1), k + (c0 >> 2 & 1));
                    const vec3 p1 = g.position(i + (c1 & 1), j + (c1 >> 1 & 1), k + (c1 >> 2 & 1));
                    out.positions[patchVertex[patch]] += p0 + (p1 - p0) * (v[c0] / (v[c0] - v[c1]));
                    slot[e] = patchVertex[patch];
                }
                for (int patch = 0; patch < 12; ++patch)
                    if (patchCrossings[patch] > 0)
                        out.positions[patchVertex[patch]] /= float(patchCrossings[patch]);
            }

    // One quad per crossed grid edge, joining the patches of the four cells around it.
    const int cycle[4][2] = { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 } }; // counter-clockwise about the edge's axis
    for (int k = 1; k < cells.z; ++k)
        for (int j = 1; j < cells.y; ++j)
            for (int i = 1; i < cells.x; ++i)
                for (int a = 0; a < 3; ++a) {
                    glm::ivec3 lo(i, j, k), hi = lo;
                    hi[a] += 1;
                    const bool in0 = inside(g.values[g.index(lo.x, lo.y, lo.z)]);
                    if (in0 == inside(g.values[g.index(hi.x, hi.y, hi.z)]))
                        continue;
                    std::array<std::uint32_t, 4> quad{};
                    for (int q = 0; q < 4; ++q) {
                        glm::ivec3 c = lo;
                        c[(a + 1) % 3] -= 1 - cycle[q][0];
                        c[(a + 2) % 3] -= 1 - cycle[q][1];
                        const std::uint32_t s = cellSlot[(std::size_t(c.z) * cells.y + c.y) * cells.x + c.x];
                        quad[q] = edgeVertex[s][4 * a + (1 - cycle[q][0]) + 2 * (1 - cycle[q][1])];
                    }
                    if (!in0) // outside at the low end: the surface faces -axis
                        std::swap(quad[1], quad[3]);
                    out.quads.push_back(quad);
                }
    return out;
}

// Moves each vertex onto the zero set with one Newton step along the distance gradient (the
// surface-nets vertex is already within a fraction of a cell). The step is capped so a vertex in
// a tight crease cannot jump across to the other side.
void projectToSurface(std::vector<vec3>& positions)
{
    constexpr float h = 0.0004f;
    for (vec3& p : positions) {
        const float d = headDistance(p);
        const vec3 grad = (vec3(headDistance(p + vec3(h, 0.0f, 0.0f)), headDistance(p + vec3(0.0f, h, 0.0f)),
                               headDistance(p + vec3(0.0f, 0.0f, h)))
                              - d)
            / h;
        const float g2 = glm::dot(grad, grad);
        if (!(g2 > 1e-6f))
            continue;
        vec3 step = grad * (d / g2);
        const float len = glm::length(step);
        if (len > 0.5f * kCell)
            step *= 0.5f * kCell / len;
        p -= step;
    }
}

// Taubin smoothing (a shrinking step then an inflating one): evens out the grid's stair pattern
// without the volume loss of plain Laplacian smoothing.
void taubinSmooth(QuadMesh& mesh, int iterations)
{
    std::vector<std::vector<std::uint32_t>> neighbours(mesh.positions.size());
    for (const auto& q : mesh.quads)
        for (int k = 0; k < 4; ++k)
            neighbours[q[k]].push_back(q[(k + 1) % 4]); // each quad edge appears once per side
    for (auto& n : neighbours) {
        std::sort(n.begin(), n.end());
        n.erase(std::unique(n.begin(), n.end()), n.end());
    }
    std::vector<vec3> moved(mesh.positions.size());
    for (int it = 0; it < 2 * iterations; ++it) {
        const float factor = it % 2 == 0 ? 0.5f : -0.53f;
        for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
            vec3 mean(0.0f);
            for (std::uint32_t n : neighbours[v])
                mean += mesh.positions[n];
            mean /= float(std::max<std::size_t>(neighbours[v].size(), 1));
            moved[v] = mesh.positions[v] + factor * (mean - mesh.positions[v]);
        }
        mesh.positions.swap(moved);
    }
}

TriangleMesh triangulate(const QuadMesh& quads)
{
    TriangleMesh mesh;
    mesh.positions = quads.positions;
    mesh.triangles.reserve(2 * quads.quads.size());
    for (const auto& q : quads.quads) {
        const auto& p = quads.positions;
        // Cut along the shorter diagonal: the flatter, better-shaped pair of triangles.
        if (glm::distance(p[q[0]], p[q[2]]) <= glm::distance(p[q[1]], p[q[3]])) {
            mesh.triangles.emplace_back(q[0], q[1], q[2]);
            mesh.triangles.emplace_back(q[0], q[2], q[3]);
        } else {
            mesh.triangles.emplace_back(q[1], q[2], q[3]);
            mesh.triangles.emplace_back(q[1], q[3], q[0]);
        }
    }
    return mesh;
}

// --- Growth map ---------------------------------------------------------------------------------

// The hairline as a polyline over (arc length around the head at azimuth from the face, height):
// forehead, temples, sideburns, over the ears, behind them and down to the nape.
constexpr float kHairlineRadius = 0.08f;
struct HairlinePoint {
    float azimuthDegrees;
    float y;
};
constexpr HairlinePoint kHairline[] = {
    { 0.0f, 0.078f },
    { 25.0f, 0.075f },
    { 42.0f, 0.064f },
    { 55.0f, 0.055f },
    { 64.0f, 0.035f },
    { 67.0f, -0.002f },
    { 80.0f, -0.002f },
    { 84.0f, 0.036f },
    { 100.0f, 0.038f },
    { 106.0f, 0.032f },
    { 112.0f, -0.005f },
    { 118.0f, -0.035f },
    { 150.0f, -0.060f },
    { 180.0f, -0.068f },
};

// Angle in radians between +Z and (|x|, z) around the Y axis, 0 at the face to pi at the back. A
// polynomial atan (error < 3e-4 rad, under 0.03 mm of scalp) from +, -, * and / only: libm's
// atan2 may round differently from one platform to the next, and the weights must not.
float azimuthFromFace(float x, float z)
{
    constexpr float kHalfPi = 1.57079633f, kPi = 3.14159265f;
    const float ax = std::abs(x), az = std::abs(z);
    const float hi = std::max(ax, az);
    if (hi == 0.0f)
        return 0.0f;
    const float a = std::min(ax, az) / hi, s = a * a;
    float angle = ((-0.0464964749f * s + 0.15931422f) * s - 0.327622764f) * s * a + a;
    if (ax > az)
        angle = kHalfPi - angle;
    return z < 0.0f ? kPi - angle : angle;
}

// Signed distance in the (arc, height) plane to the hairline: positive above it, on the scalp.
float aboveHairline(vec3 p)
{
    const float azimuth = azimuthFromFace(p.x, p.z + 0.008f);
    const vec2 q{ azimuth * kHairlineRadius, p.y };
    float nearest = 1e9f;
    float lineY = kHairline[0].y;
    constexpr float kDeg = 3.14159265f / 180.0f;
    for (std::size_t s = 0; s + 1 < std::size(kHairline); ++s) {
        const vec2 a{ kHairline[s].azimuthDegrees * kDeg * kHairlineRadius, kHairline[s].y };
        const vec2 b{ kHairline[s + 1].azimuthDegrees * kDeg * kHairlineRadius, kHairline[s + 1].y };
        const float h = glm::clamp(glm::dot(q - a, b - a) / glm::dot(b - a, b - a), 0.0f, 1.0f);
        nearest = std::min(nearest, glm::distance(q, a + (b - a) * h));
        if (q.x >= a.x && q.x <= b.x)
            lineY = a.y + (b.y - a.y) * (q.x - a.x) / (b.x - a.x);
    }
    return q.y > lineY ? nearest : -nearest;
}

std::vector<float> growthMap(const TriangleMesh& mesh)
{
    std::vector<float> weights(mesh.positions.size());
    for (std::size_t v = 0; v < weights.size(); ++v) {
        const vec3 p = mesh.positions[v];
        // ~1 cm soft edge at the hairline; the ear and its root stay bare.
        const float scalp = glm::smoothstep(-0.005f, 0.005f, aboveHairline(p));
        const float offEar = glm::smoothstep(0.0f, 0.005f, earDistance(vec3(std::abs(p.x), p.y, p.z)));
        weights[v] = glm::clamp(scalp * offEar, 0.0f, 1.0f);
    }
    return weights;
}

} // namespace

DefaultHead makeDefaultHead()
{
    QuadMesh quads = contour(sampleHead());
    projectToSurface(quads.positions);
    taubinSmooth(quads, 3);
    DefaultHead head;
    head.mesh = triangulate(quads);
    head.growthWeights = growthMap(head.mesh);
    return head;
}

} // namespace wisp
