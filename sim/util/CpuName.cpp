#include "sim/util/CpuName.h"

#include <cstring>
#include <fstream>
#include <sstream>

#if defined(__x86_64__) || defined(__i386__)
#include <cpuid.h>
#endif

namespace wisp {

std::string collapsedSpaces(const std::string& text)
{
    std::string out;
    for (char c : text) {
        if (c == '\0')
            break;
        const bool space = c == ' ' || c == '\t';
        if (space && (out.empty() || out.back() == ' '))
            continue;
        out += space ? ' ' : c;
    }
    while (!out.empty() && out.back() == ' ')
        out.pop_back();
    return out;
}

std::string cpuModelFromCpuinfo(const std::string& cpuinfo)
{
    std::istringstream in(cpuinfo);
    std::string line;
    while (std::getline(in, line)) {
        const auto colon = line.find(':');
        if (colon == std::string::npos)
            continue;
        const std::string key = collapsedSpaces(line.substr(0, colon));
        if (key == "model name" || key == "cpu model" || key == "Model" || key == "Hardware") {
            std::string value = collapsedSpaces(line.substr(colon + 1));
            if (!value.empty())
                return value;
        }
    }
    return {};
}

namespace {

std::string brandString()
{
#if defined(__x86_64__) || defined(__i386__)
    unsigned a = 0, b = 0, c = 0, d = 0;
    if (__get_cpuid(0x80000000u, &a, &b, &c, &d) == 0 || a < 0x80000004u)
        return {};
    char brand[49] = {};
    for (unsigned leaf = 0; leaf < 3; ++leaf) {
        unsigned r[4] = {};
        __get_cpuid(0x80000002u + leaf, &r[0], &r[1], &r[2], &r[3]);
        std::memcpy(brand + 16 * leaf, r, sizeof r);
    }
    return collapsedSpaces(brand);
#else
    return {};
#endif
}

} // namespace

std::string cpuModelName()
{
    // Looked up once (every bench row prints it): the CPU does not change under a running process.
    static const std::string name = [] {
        std::string found = brandString();
        if (found.empty()) {
            std::ifstream in("/proc/cpuinfo");
            std::ostringstream text;
            text << in.rdbuf();
            found = cpuModelFromCpuinfo(text.str());
        }
        return found.empty() ? std::string("unknown CPU") : found;
    }();
    return name;
}

} // namespace wisp
