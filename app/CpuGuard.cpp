// Refuses to start, with a message, on a CPU that lacks an instruction set this build was compiled
// for. The default build needs x86-64-v2 with AES (2010 on) and picks its solver's SIMD target at
// run time; a WISP_NATIVE or WISP_MARCH build is compiled for the build machine's CPU or the one
// named (CMakeLists.txt), and started on a CPU without those instructions it would otherwise die
// with SIGILL somewhere, with nothing said. Linked into wisp and wisp-cli.
//
// The check runs as a high-priority constructor, before every other static initialiser of the
// executable, and is itself compiled for the x86-64 baseline (target("arch=x86-64")), so it runs on
// any x86-64 CPU whatever -march the rest of the build used. The macros below say what the rest of
// this translation unit was allowed to use, which is what every file of the build was.

#include <cstdio>
#include <cstdlib>
#include <cstring>

#if defined(__x86_64__) && defined(__GNUC__)

namespace {

struct Feature {
    const char* name; // as __builtin_cpu_supports and /proc/cpuinfo spell it (mostly)
    bool built; // and this CPU has it
};

// Exit status of a program that cannot run on this CPU (wisp-cli's 0, 1 and 2 are taken).
constexpr int kCpuLacksInstructions = 3;

__attribute__((constructor(101), target("arch=x86-64"))) void refuseAMissingInstructionSet()
{
    __builtin_cpu_init();
    Feature features[] = {
#if defined(__AVX512F__)
        { "avx512f", __builtin_cpu_supports("avx512f") != 0 },
#endif
#if defined(__AVX512BW__)
        { "avx512bw", __builtin_cpu_supports("avx512bw") != 0 },
#endif
#if defined(__AVX512DQ__)
        { "avx512dq", __builtin_cpu_supports("avx512dq") != 0 },
#endif
#if defined(__AVX512VL__)
        { "avx512vl", __builtin_cpu_supports("avx512vl") != 0 },
#endif
#if defined(__AVX512CD__)
        { "avx512cd", __builtin_cpu_supports("avx512cd") != 0 },
#endif
#if defined(__AVX512VBMI__)
        { "avx512vbmi", __builtin_cpu_supports("avx512vbmi") != 0 },
#endif
#if defined(__AVX512VNNI__)
        { "avx512vnni", __builtin_cpu_supports("avx512vnni") != 0 },
#endif
#if defined(__AVX512BF16__)
        { "avx512bf16", __builtin_cpu_supports("avx512bf16") != 0 },
#endif
#if defined(__AVX2__)
        { "avx2", __builtin_cpu_supports("avx2") != 0 },
#endif
#if defined(__FMA__)
        { "fma", __builtin_cpu_supports("fma") != 0 },
#endif
#if defined(__AVX__)
        { "avx", __builtin_cpu_supports("avx") != 0 },
#endif
#if defined(__BMI2__)
        { "bmi2", __builtin_cpu_supports("bmi2") != 0 },
#endif
#if defined(__SSE4_2__)
        { "sse4.2", __builtin_cpu_supports("sse4.2") != 0 },
#endif
#if defined(__POPCNT__)
        { "popcnt", __builtin_cpu_supports("popcnt") != 0 },
#endif
#if defined(__AES__)
        { "aes", __builtin_cpu_supports("aes") != 0 },
#endif
#if defined(__PCLMUL__)
        { "pclmul", __builtin_cpu_supports("pclmul") != 0 },
#endif
        { "sse2", true }, // the x86-64 baseline
    };
    // WISP_TEST_CPU_LACKS=NAME pretends this CPU lacks NAME (one of the names above), so a test can
    // see the refusal on a machine that has everything.
    const char* pretend = std::getenv("WISP_TEST_CPU_LACKS");
    bool missing = false;
    for (Feature& f : features) {
        if (pretend && std::strcmp(pretend, f.name) == 0)
            f.built = false;
        missing = missing || !f.built;
    }
    if (!missing)
        return;
    std::fputs("Wisp: this build was compiled for instructions this CPU does not have:", stderr);
    for (const Feature& f : features)
        if (!f.built)
            std::fprintf(stderr, " %s", f.name);
    std::fputs(".\nIt was built for a CPU that has them (WISP_NATIVE=ON compiles for the machine that builds it, "
               "WISP_MARCH for the CPU it names).\n"
               "Build it on this machine (scripts/setup.sh), or configure with -DWISP_NATIVE=OFF -DWISP_MARCH= for "
               "the default build, which runs on any x86-64 CPU with SSE4.2 and AES (2010 on) and picks the "
               "best SIMD it has at run time.\n",
        stderr);
    std::_Exit(kCpuLacksInstructions);
}

} // namespace

#endif
