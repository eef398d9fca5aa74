// Figures, not tests (Google Benchmark): how long reading a head takes. CI builds this target so
// that it keeps compiling, and never runs it: shared machines are too noisy for a time to be a
// pass or a fail. Run it by hand: build/tests/wisp_benchmarks --benchmark_filter=ReadHead
// --benchmark_repetitions=5 (the README's load figure is the best of 5).

#include "io/MeshReader.h"

#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>

namespace {

std::filesystem::path asset(const char* relative)
{
    return std::filesystem::path(WISP_SHARED_ASSETS) / relative;
}

void ReadHead(benchmark::State& state, const char* relative)
{
    const std::string path = asset(relative).string();
    if (!std::filesystem::exists(path)) {
        state.SkipWithError(("shared asset " + path + " is absent").c_str());
        return;
    }
    std::size_t triangles = 0;
    for (auto _ : state) {
        const wisp::io::Result<wisp::io::MeshReadResult> read = wisp::io::readMesh(path);
        if (!read) {
            state.SkipWithError(read.error().toString().c_str());
            return;
        }
        triangles = read.value().mesh.triangleCount();
        benchmark::DoNotOptimize(triangles);
    }
    state.counters["triangles"] = static_cast<double>(triangles);
    state.SetBytesProcessed(
        static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(std::filesystem::file_size(path)));
}

BENCHMARK_CAPTURE(ReadHead, igea_tristrips_ply, "heads/igea_tristrips.ply")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(ReadHead, cy_woman_head_ply, "heads/cy_woman_head.ply")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(ReadHead, max_planck_obj, "heads/max_planck_decimated.obj")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(ReadHead, cylinder_engine_glb, "gltf/2CylinderEngine.glb")->Unit(benchmark::kMillisecond);

} // namespace
