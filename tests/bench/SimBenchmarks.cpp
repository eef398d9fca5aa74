// Figures, not tests (Google Benchmark), moved out of the test suite where they only printed:
// a scalp-brush dab, a signed-distance-field bake and BVH queries. CI builds, never times them.

#include "../sim/MeshFixtures.h"
#include "sim/geometry/DefaultHead.h"
#include "sim/geometry/MeshBvh.h"
#include "sim/geometry/SignedDistanceField.h"
#include "sim/groom/ScalpBrush.h"

#include <benchmark/benchmark.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <random>
#include <vector>

namespace wisp {
namespace {

// 100 dabs of 2 cm, mirrored, along the upper half of a mesh: Add (state.range(1) == 0) or Smooth.
void Dab(benchmark::State& state, const TriangleMesh& mesh)
{
    const ScalpBrush brush(mesh);
    std::vector<float> weights(mesh.vertexCount(), 0.3f);
    std::vector<glm::vec3> centres;
    std::mt19937 rng(9);
    while (centres.size() < 100)
        if (const glm::vec3 p = mesh.positions[rng() % mesh.positions.size()]; p.y > 0.03f)
            centres.push_back(p);
    const BrushMode mode = state.range(0) == 0 ? BrushMode::Add : BrushMode::Smooth;
    std::size_t next = 0;
    for (auto _ : state) {
        const auto changed = brush.dab(
            centres[next++ % centres.size()], BrushSettings{ .radiusMetres = 0.02f, .mode = mode }, weights);
        benchmark::DoNotOptimize(changed.size());
    }
}

void DabDefaultHead(benchmark::State& state)
{
    static const TriangleMesh head = makeDefaultHead().mesh;
    Dab(state, head);
}
BENCHMARK(DabDefaultHead)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

void DabDenseSphere(benchmark::State& state)
{
    static const TriangleMesh dense = test::makeIcosphere(0.1f, 7); // 327,680 triangles on a 10 cm sphere
    Dab(state, dense);
}
BENCHMARK(DabDenseSphere)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

void PrepareBrushDenseSphere(benchmark::State& state)
{
    const TriangleMesh dense = test::makeIcosphere(0.1f, 7);
    for (auto _ : state)
        benchmark::DoNotOptimize(ScalpBrush(dense));
}
BENCHMARK(PrepareBrushDenseSphere)->Unit(benchmark::kMillisecond);

// The real head scaled to a 0.25 m box, at 2.5 mm cells with a 2 cm margin.
void BakeHeadSdf(benchmark::State& state)
{
    if (!std::filesystem::exists(test::planckPath())) {
        state.SkipWithError("the shared head max_planck_decimated.obj is absent");
        return;
    }
    TriangleMesh head = test::readObj(test::planckPath(), 1.0f);
    const Aabb box = boundsOf(head);
    const float scale = 0.25f / std::max(box.size().x, std::max(box.size().y, box.size().z));
    for (glm::vec3& p : head.positions)
        p = (p - box.center()) * scale;
    for (auto _ : state) {
        const SignedDistanceField field = SignedDistanceField::bake(head, 0.0025f, 0.02f);
        benchmark::DoNotOptimize(field.empty());
    }
    state.counters["triangles"] = static_cast<double>(head.triangleCount());
}
BENCHMARK(BakeHeadSdf)->Unit(benchmark::kMillisecond);

const TriangleMesh& bvhSphere()
{
    static const TriangleMesh sphere = test::makeIcosphere(0.12f, 7); // 327,680 triangles
    return sphere;
}

void BuildBvh(benchmark::State& state)
{
    for (auto _ : state)
        benchmark::DoNotOptimize(MeshBvh(bvhSphere()));
}
BENCHMARK(BuildBvh)->Unit(benchmark::kMillisecond);

void RaycastBvh(benchmark::State& state)
{
    const MeshBvh bvh(bvhSphere());
    std::mt19937 rng(5);
    std::normal_distribution<float> gauss;
    for (auto _ : state) {
        const glm::vec3 d = glm::normalize(glm::vec3(gauss(rng), gauss(rng), gauss(rng)) + glm::vec3(1e-6f));
        benchmark::DoNotOptimize(bvh.raycast(-0.5f * d, d, 1.0f).has_value());
    }
}
BENCHMARK(RaycastBvh);

void ClosestPointBvh(benchmark::State& state)
{
    const MeshBvh bvh(bvhSphere());
    std::mt19937 rng(5);
    std::normal_distribution<float> gauss;
    for (auto _ : state) { // within a few centimetres of the surface, where grooming asks
        const glm::vec3 d = glm::normalize(glm::vec3(gauss(rng), gauss(rng), gauss(rng)) + glm::vec3(1e-6f));
        benchmark::DoNotOptimize(bvh.closestPoint((0.12f + 0.01f * gauss(rng)) * d).distance);
    }
}
BENCHMARK(ClosestPointBvh);

} // namespace
} // namespace wisp
