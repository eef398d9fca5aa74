// The default scene's simulated strands after a number of steps on one SIMD target, written to
// stdout as raw little-endian floats (x, y, z per particle): what scripts/arm64-check.sh compares
// between this machine's x86 build and an aarch64 build run under qemu-user. Only sim/ and the sim
// tests' set-up (the built-in head, the editor's default groom, wind and volume).
//
//   default-scene STEPS THREADS [TARGET] > positions.f32   (stderr: the target that ran and the count)
//   default-scene --targets                                (the targets this CPU runs, best first)

#include "sim/util/SimdTarget.h"
#include "tests/sim/SimFixtures.h"

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

int main(int argc, char** argv)
{
    if (argc == 2 && std::string(argv[1]) == "--targets") {
        for (const std::string& target : wisp::availableSimdTargets())
            std::printf("%s\n", target.c_str());
        return 0;
    }
    const int steps = argc >= 3 ? std::atoi(argv[1]) : 0;
    const int threads = argc >= 3 ? std::atoi(argv[2]) : 0;
    if (argc < 3 || argc > 4 || steps < 1 || threads < 1) {
        std::fprintf(stderr, "usage: %s STEPS THREADS [TARGET] > positions.f32 | --targets\n", argv[0]);
        return 2;
    }
    if (argc == 4) {
        const std::string error = wisp::forceSimdTarget(argv[3]);
        if (!error.empty()) {
            std::fprintf(stderr, "%s\n", error.c_str());
            return 2;
        }
    }
    try {
        auto sim = wisp::test::makeSimulation(wisp::ParameterValues{}, threads);
        wisp::test::run(*sim, steps);
        std::vector<glm::vec3> p;
        sim->copySimulated(p);
        if (std::fwrite(p.data(), sizeof(glm::vec3), p.size(), stdout) != p.size()) {
            std::fprintf(stderr, "could not write the positions\n");
            return 1;
        }
        std::fprintf(stderr, "%s: %zu particles after %d steps\n", wisp::solverSimdTarget(), p.size(), steps);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 1;
    }
    return 0;
}
