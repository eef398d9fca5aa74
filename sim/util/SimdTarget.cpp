#include "sim/util/SimdTarget.h"

#include <algorithm>
#include <cctype>
#include <cstdint>

// A function per target that says which it is: dispatched as the kernels are, it names the target
// they run on.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "sim/util/SimdTarget.cpp"
#include <hwy/foreach_target.h> // (before highway.h)

#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace wisp::HWY_NAMESPACE {
std::int64_t runningTarget()
{
    return HWY_TARGET;
}
} // namespace wisp::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE

namespace wisp {

HWY_EXPORT(runningTarget);

namespace {

const char* nameOf(std::int64_t target)
{
    switch (target) {
#if HWY_ARCH_X86
    case HWY_AVX3_DL:
    case HWY_AVX3:
        return "AVX-512";
    case HWY_AVX2:
        return "AVX2";
    case HWY_SSE4:
        return "SSE4";
    case HWY_SSSE3:
        return "SSSE3";
#elif HWY_ARCH_ARM
    case HWY_NEON:
        return "NEON";
    case HWY_SVE:
    case HWY_SVE_256:
        return "SVE";
    case HWY_SVE2:
    case HWY_SVE2_128:
        return "SVE2";
#endif
    case HWY_EMU128:
        return "EMU128";
    case HWY_SCALAR:
        return "scalar";
    default:
        return hwy::TargetName(target);
    }
}

int floatsOf(std::int64_t target)
{
#if HWY_ARCH_X86
    if (target == HWY_AVX3_DL || target == HWY_AVX3)
        return 16;
    if (target == HWY_AVX2)
        return 8;
#endif
    return target == HWY_SCALAR ? 1 : 4;
}

std::string upper(std::string s)
{
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
    return s;
}

// The targets compiled in that this CPU runs, whatever is forced now.
std::vector<std::int64_t> runnableTargets(std::int64_t forced)
{
    hwy::SetSupportedTargetsForTest(0);
    std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets(); // lowest bit (best) first
    hwy::SetSupportedTargetsForTest(forced);
    return targets;
}

std::int64_t g_forced = 0; // the target forceSimdTarget() chose (0: none)

} // namespace

const char* solverSimdTarget()
{
    return nameOf(HWY_DYNAMIC_DISPATCH(runningTarget)());
}

int solverVectorFloats()
{
    return floatsOf(HWY_DYNAMIC_DISPATCH(runningTarget)());
}

std::vector<std::string> availableSimdTargets()
{
    std::vector<std::string> names;
    for (const std::int64_t t : runnableTargets(g_forced))
        if (std::find(names.begin(), names.end(), nameOf(t)) == names.end())
            names.push_back(nameOf(t));
    return names;
}

std::string forceSimdTarget(const std::string& name)
{
    std::string wanted = upper(name);
    if (wanted == "AVX3" || wanted == "AVX512")
        wanted = "AVX-512";
    if (wanted.empty()) {
        g_forced = 0;
        hwy::SetSupportedTargetsForTest(0);
        return {};
    }
    std::string available;
    for (const std::int64_t t : runnableTargets(g_forced)) {
        if (upper(nameOf(t)) == wanted) {
            // This target and none better: the dispatch takes the best one supported.
            g_forced = t;
            hwy::SetSupportedTargetsForTest(t);
            return {};
        }
        available += std::string(available.empty() ? "" : ", ") + nameOf(t);
    }
    return "no SIMD target '" + name + "' in this binary for this CPU (there are: " + available + ")";
}

} // namespace wisp

#endif // HWY_ONCE
