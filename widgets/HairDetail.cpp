#include "widgets/HairDetail.h"

#include <algorithm>
#include <cmath>

namespace wisp {

float HairDetail::fraction(std::size_t strands) const
{
    if (!m_previewing || strands <= kMinimumStrands)
        return 1.0f;
    const float floor = std::max(kMinimumFraction, static_cast<float>(kMinimumStrands) / static_cast<float>(strands));
    return std::clamp(m_fraction, floor, 1.0f);
}

void HairDetail::reset()
{
    m_previewing = false;
    m_fraction = 1.0f;
}

void HairDetail::paintTook(double milliseconds, bool previewed, float fractionDrawn, std::size_t strands)
{
    if (!std::isfinite(milliseconds) || milliseconds <= 0.0 || !(fractionDrawn > 0.0f))
        return;
    if (strands <= kMinimumStrands) {
        reset();
        return;
    }
    const double ratio = kBudgetMilliseconds / milliseconds;
    if (!previewed) {
        // Full detail was too slow: coarser curves first, all strands; the next paint tells more.
        if (ratio < 0.95) {
            m_previewing = true;
            m_fraction = 1.0f;
        }
        return;
    }
    // Paint time is fixed work (head, background) plus work in proportion to the strands drawn, so
    // scaling the fraction by budget / time undershoots a little when cutting and overshoots a
    // little when growing; the dead band and step limits keep it from oscillating.
    if (ratio < 0.95) {
        m_fraction = fractionDrawn * static_cast<float>(std::max(ratio, 0.5));
    } else if (ratio > 1.3) {
        if (fractionDrawn >= 1.0f && ratio > 2.0)
            m_previewing = false; // even full detail (about twice the preview's work) should fit
        else
            m_fraction = fractionDrawn * static_cast<float>(std::min(ratio * 0.9, 1.25));
    }
    m_fraction = std::clamp(m_fraction, kMinimumFraction, 1.0f);
}

} // namespace wisp
