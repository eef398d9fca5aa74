#pragma once
// The SDF bake's exact band (SdfBake.h, pass 1) for one triangle, compiled once per SIMD target like
// the solver's kernels (SdfBandRow.cpp): the squared distance from each of a list of samples to the
// triangle, as many samples at a time as a register holds (the list runs across rows, so short rows
// of small triangles still fill the register), kept where it is below the sample's value.
// The same bits as closestPointOnTriangle (MeshBvh.h) sample by sample, on every target: the same
// operations in the same order, each lane taking the first of Ericson's regions it lies in.

#include <cstddef>
#include <cstdint>

namespace wisp::sdf_detail {

struct BakeTriangle;

// The lists' length is a multiple of this (the widest register's floats: AVX-512's 16), so whole
// registers can be loaded; `count` says how many are samples.
constexpr std::size_t kBandSamplePadding = 16;

// The samples the band visits for one triangle: positions (metres, as Grid::position computes
// them) and where each sample's value is.
struct BandSamples {
    float* x = nullptr;
    float* y = nullptr;
    float* z = nullptr;
    std::uint32_t* index = nullptr;
    std::size_t count = 0;
};

// values[index[n]] = min(values[index[n]], |closest point of the triangle - sample n|²) for every n.
void bandSamples(const BakeTriangle& triangle, const BandSamples& samples, float* values);

} // namespace wisp::sdf_detail
