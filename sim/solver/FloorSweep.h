#pragma once
// The memory floor of a hair step: a minimal single-sweep follow-the-leader pass over a given
// number of particles, which reads and writes each particle's position and previous position once
// (Verlet under gravity) and applies one length constraint to its parent (Müller et al. 2012,
// "Fast Simulation of Inextensible Hair and Fur"), nothing else: no bending, no contact, no wind.
// Laid out as the solver's blocks of 16 strands (SolverLanes.h) and run on a ThreadPool as the
// solver's step is, so `wisp-cli bench` can say how far a workload is from what this machine's
// memory and cores allow, measured in the same run.
//
// Thread: one owner thread calls everything.

#include "sim/util/ThreadPool.h"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace wisp {

class FloorSweep {
public:
    // At least `particles` particles in strands of `pointsPerStrand` (at least 2; the last block of
    // 16 strands padded), hanging straight down at rest from roots 1 cm apart, 0.3 m long, on
    // `threadCount` threads (0: one per core).
    FloorSweep(std::size_t particles, std::uint32_t pointsPerStrand, int threadCount);
    // The same on a pool it shares (a solver's, Solver::threadPool()), which must outlive it: the
    // bench times the floor's steps between the workload's on the same threads, so neither pool's
    // workers spin on a core the other's need.
    FloorSweep(std::size_t particles, std::uint32_t pointsPerStrand, ThreadPool& pool);

    // One step of 1/60 s: every particle but the roots moves once.
    void step();

    std::size_t particleCount() const { return m_particles; }
    std::size_t strandCount() const { return m_strands; }
    int threadCount() const { return m_pool->threadCount(); }
    std::uint32_t pointsPerStrand() const { return m_points; }
    float segmentMetres() const { return m_segmentMetres; }
    // Bytes the sweep reads and writes per step (positions and previous positions, once each way).
    std::size_t bytesPerStep() const { return m_rows.size() * sizeof(float) * 2; }
    // Strand s's point j, in metres (for tests).
    float x(std::size_t strand, std::uint32_t point) const { return at(strand, point, 0); }
    float y(std::size_t strand, std::uint32_t point) const { return at(strand, point, 1); }
    float z(std::size_t strand, std::uint32_t point) const { return at(strand, point, 2); }
    // Pushes every non-root particle by (dx, 0, dz) metres, so a test can watch it swing back.
    void displace(float dxMetres, float dzMetres);

private:
    FloorSweep(
        std::size_t particles, std::uint32_t pointsPerStrand, std::unique_ptr<ThreadPool> ownPool, ThreadPool* pool);
    float at(std::size_t strand, std::uint32_t point, int field) const;

    std::unique_ptr<ThreadPool> m_ownPool; // none when it runs on a pool it was given
    ThreadPool* m_pool = nullptr;
    std::uint32_t m_points = 0;
    std::size_t m_strands = 0;
    std::size_t m_blocks = 0;
    std::size_t m_particles = 0;
    float m_segmentMetres = 0.0f;
    std::vector<float> m_rows; // per block, per point: x, y, z, px, py, pz, 16 strands each
};

} // namespace wisp
