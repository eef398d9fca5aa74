#include "sim/geometry/DefaultHead.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>

namespace wisp {
namespace {

// Built once: every test reads the same head.
const DefaultHead& head()
{
    static const DefaultHead h = makeDefaultHead();
    return h;
}

// Lowest point of the face: the neck's front never reaches z > 0.06, the chin does.
float chinY(const TriangleMesh& mesh)
{
    float y = 1.0f;
    for (const glm::vec3& p : mesh.positions)
        if (p.z > 0.06f && std::abs(p.x) < 0.02f)
            y = std::min(y, p.y);
    return y;
}

std::size_t nearestVertex(const TriangleMesh& mesh, glm::vec3 to)
{
    std::size_t best = 0;
    for (std::size_t v = 1; v < mesh.positions.size(); ++v)
        if (glm::distance(mesh.positions[v], to) < glm::distance(mesh.positions[best], to))
            best = v;
    return best;
}

TEST(DefaultHead, IsAValidMeshOfTheRightSize)
{
    const TriangleMesh& mesh = head().mesh;
    EXPECT_EQ(validateMesh(mesh), "");
    EXPECT_GE(mesh.triangleCount(), 10000u);
    EXPECT_LE(mesh.triangleCount(), 40000u);
}

TEST(DefaultHead, IsClosedManifoldAndConsistentlyOriented)
{
    const TriangleMesh& mesh = head().mesh;
    // Consistent orientation means each directed edge appears once and its reverse once: that also
    // makes every undirected edge shared by exactly two triangles (closed, no fins).
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
    for (const glm::uvec3& t : mesh.triangles)
        for (int k = 0; k < 3; ++k)
            ++directed[{ t[k], t[(k + 1) % 3] }];
    std::size_t wrong = 0;
    for (const auto& [edge, count] : directed)
        if (count != 1 || directed.count({ edge.second, edge.first }) != 1)
            ++wrong;
    EXPECT_EQ(wrong, 0u);

    // Every vertex's fan closes into a single loop: no two sheets pinched together at a vertex.
    std::vector<std::map<std::uint32_t, std::uint32_t>> fan(mesh.vertexCount());
    for (const glm::uvec3& t : mesh.triangles)
        for (int k = 0; k < 3; ++k)
            fan[t[k]][t[(k + 1) % 3]] = t[(k + 2) % 3];
    std::size_t pinched = 0;
    for (const auto& next : fan) {
        if (next.empty()) {
            ++pinched; // an unused vertex
            continue;
        }
        const std::uint32_t start = next.begin()->first;
        std::uint32_t at = start;
        std::size_t steps = 0;
        do {
            const auto it = next.find(at);
            if (it == next.end())
                break;
            at = it->second;
            ++steps;
        } while (at != start && steps <= next.size());
        if (at != start || steps != next.size())
            ++pinched;
    }
    EXPECT_EQ(pinched, 0u);

    // Euler characteristic of a sphere: the head has no handles.
    const auto v = static_cast<long long>(mesh.vertexCount()), f = static_cast<long long>(mesh.triangleCount());
    EXPECT_EQ(v - f * 3 / 2 + f, 2);
}

TEST(DefaultHead, FacesOutwardWithAHeadsVolume)
{
    const TriangleMesh& mesh = head().mesh;
    double volume = 0.0;
    for (const glm::uvec3& t : mesh.triangles)
        volume += double(glm::dot(mesh.positions[t.x], glm::cross(mesh.positions[t.y], mesh.positions[t.z]))) / 6.0;
    EXPECT_GT(volume, 3e-3);
    EXPECT_LT(volume, 7e-3);
}

TEST(DefaultHead, HasNoDegenerateTriangles)
{
    const TriangleMesh& mesh = head().mesh;
    for (std::uint32_t t = 0; t < mesh.triangleCount(); ++t) {
        const glm::uvec3 tri = mesh.triangles[t];
        ASSERT_TRUE(tri.x != tri.y && tri.y != tri.z && tri.z != tri.x) << "triangle " << t;
        ASSERT_GT(triangleArea(mesh, t), 1e-8f) << "triangle " << t; // cells are ~1.4e-5 m²
    }
}

TEST(DefaultHead, HasHumanProportions)
{
    const TriangleMesh& mesh = head().mesh;
    const Aabb box = boundsOf(mesh);
    EXPECT_GT(box.max.y, 0.11f); // crown
    EXPECT_LT(box.max.y, 0.13f);
    const float chin = chinY(mesh);
    EXPECT_GT(box.max.y - chin, 0.22f); // chin to crown
    EXPECT_LT(box.max.y - chin, 0.245f);
    EXPECT_GT(chin - box.min.y, 0.08f); // the neck below the chin
    EXPECT_LT(chin - box.min.y, 0.12f);

    // Width of the skull above the ears, and with the ears.
    float skullHalfWidth = 0.0f;
    for (const glm::vec3& p : mesh.positions)
        if (p.y > 0.045f)
            skullHalfWidth = std::max(skullHalfWidth, std::abs(p.x));
    EXPECT_GT(2.0f * skullHalfWidth, 0.14f);
    EXPECT_LT(2.0f * skullHalfWidth, 0.16f);
    EXPECT_GT(box.size().x, 0.15f);
    EXPECT_LT(box.size().x, 0.19f);

    // Depth from brow to the back of the skull (above the nose), and with the nose.
    float front = -1.0f, back = 1.0f;
    for (const glm::vec3& p : mesh.positions)
        if (p.y > 0.015f) {
            front = std::max(front, p.z);
            back = std::min(back, p.z);
        }
    EXPECT_GT(front - back, 0.185f);
    EXPECT_LT(front - back, 0.205f);
    EXPECT_LT(box.size().z, 0.235f);

    // The cranium is centred near the origin.
    EXPECT_LT(std::abs(box.center().x), 0.005f);
    EXPECT_LT(std::abs(0.5f * (front + back)), 0.02f);
}

TEST(DefaultHead, HasAFaceAndEars)
{
    const TriangleMesh& mesh = head().mesh;
    // The nose is the most forward point, on the midline, between the chin and the brow.
    const glm::vec3 noseTip = mesh.positions[nearestVertex(mesh, glm::vec3(0.0f, 0.0f, 1.0f))];
    EXPECT_LT(std::abs(noseTip.x), 0.005f);
    EXPECT_GT(noseTip.y, chinY(mesh) + 0.05f);
    EXPECT_LT(noseTip.y, 0.0f);

    // The widest points are the ears, at eye-to-mouth height and halfway back.
    glm::vec3 widest(0.0f);
    for (const glm::vec3& p : mesh.positions)
        if (std::abs(p.x) > std::abs(widest.x))
            widest = p;
    EXPECT_GT(widest.y, -0.05f);
    EXPECT_LT(widest.y, 0.03f);
    EXPECT_GT(widest.z, -0.05f);
    EXPECT_LT(widest.z, 0.02f);

    // Eye sockets: the skin in front of the eye sits behind the brow above it.
    float brow = -1.0f, eye = -1.0f;
    for (const glm::vec3& p : mesh.positions) {
        if (std::abs(std::abs(p.x) - 0.032f) > 0.004f)
            continue;
        if (std::abs(p.y - 0.026f) < 0.003f)
            brow = std::max(brow, p.z);
        if (std::abs(p.y - 0.008f) < 0.003f)
            eye = std::max(eye, p.z);
    }
    EXPECT_LT(eye, brow - 0.002f);
}

TEST(DefaultHead, GrowthWeightsCoverTheScalpOnly)
{
    const DefaultHead& h = head();
    const TriangleMesh& mesh = h.mesh;
    ASSERT_EQ(h.growthWeights.size(), mesh.vertexCount());
    for (float w : h.growthWeights) {
        ASSERT_GE(w, 0.0f);
        ASSERT_LE(w, 1.0f);
    }
    const Aabb box = boundsOf(mesh);
    auto weightNear = [&](glm::vec3 p) { return h.growthWeights[nearestVertex(mesh, p)]; };

    EXPECT_GT(weightNear({ 0.0f, box.max.y, 0.0f }), 0.99f); // crown
    EXPECT_GT(weightNear({ 0.0f, 0.0f, box.min.z }), 0.99f); // back of the head
    EXPECT_GT(weightNear({ box.max.x, 0.06f, -0.01f }), 0.99f); // side, above the ear
    EXPECT_GT(weightNear({ 0.0f, -0.05f, -0.2f }), 0.99f); // down to the nape
    EXPECT_LT(weightNear({ 0.0f, 0.0f, 1.0f }), 0.01f); // nose tip
    EXPECT_LT(weightNear({ 0.0f, chinY(mesh), 0.1f }), 0.01f); // chin
    EXPECT_LT(weightNear({ 0.0f, 0.05f, 0.2f }), 0.01f); // forehead
    EXPECT_LT(weightNear({ box.max.x, 0.0f, 0.0f }), 0.01f); // ear

    // Neck and its cap, and the whole face below the brow, are bare.
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        const glm::vec3 p = mesh.positions[v];
        if (p.y < -0.09f || (p.z > 0.05f && p.y < 0.04f)) {
            ASSERT_EQ(h.growthWeights[v], 0.0f) << "at " << p.x << ", " << p.y << ", " << p.z;
        }
    }
}

TEST(DefaultHead, HairlineIsSoftAndPlausible)
{
    const DefaultHead& h = head();
    const TriangleMesh& mesh = h.mesh;
    // Up the middle of the forehead, weight rises from 0 to 1 over about a centimetre.
    float lastBare = -1.0f, firstFull = 1.0f;
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        const glm::vec3 p = mesh.positions[v];
        if (std::abs(p.x) > 0.01f || p.z < 0.0f || p.y < 0.03f)
            continue;
        if (h.growthWeights[v] < 0.01f)
            lastBare = std::max(lastBare, p.y);
        if (h.growthWeights[v] > 0.99f)
            firstFull = std::min(firstFull, p.y);
    }
    EXPECT_GT(lastBare, 0.065f); // a forehead's height above the brow
    EXPECT_LT(firstFull, 0.095f);
    EXPECT_GT(firstFull - lastBare, 0.004f);
    EXPECT_LT(firstFull - lastBare, 0.02f);

    // Hair covers a plausible share of the skin: the scalp is roughly a third of head and neck.
    double hairArea = 0.0, area = 0.0;
    for (std::uint32_t t = 0; t < mesh.triangleCount(); ++t) {
        const glm::uvec3 tri = mesh.triangles[t];
        const float a = triangleArea(mesh, t);
        area += a;
        hairArea += a * (h.growthWeights[tri.x] + h.growthWeights[tri.y] + h.growthWeights[tri.z]) / 3.0f;
    }
    EXPECT_GT(hairArea / area, 0.25);
    EXPECT_LT(hairArea / area, 0.5);

    // Left and right hairlines match.
    const std::size_t left = nearestVertex(mesh, { -0.07f, 0.02f, 0.02f });
    const std::size_t right = nearestVertex(mesh, { 0.07f, 0.02f, 0.02f });
    EXPECT_NEAR(h.growthWeights[left], h.growthWeights[right], 0.05f);
}

TEST(DefaultHead, IsDeterministic)
{
    const DefaultHead a = makeDefaultHead();
    const DefaultHead& b = head();
    ASSERT_EQ(a.mesh.positions.size(), b.mesh.positions.size());
    ASSERT_EQ(a.mesh.triangles.size(), b.mesh.triangles.size());
    EXPECT_TRUE(a.mesh.positions == b.mesh.positions);
    EXPECT_TRUE(a.mesh.triangles == b.mesh.triangles);
    EXPECT_TRUE(a.growthWeights == b.growthWeights);
}

} // namespace
} // namespace wisp
