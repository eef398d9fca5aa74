#include "sim/util/NumberText.h"

#include <cmath>
#include <cstdio>

namespace wisp {

std::string formatNumber(double value)
{
    if (std::isnan(value))
        return "nan";
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.6g", value);
    return buffer;
}

} // namespace wisp
