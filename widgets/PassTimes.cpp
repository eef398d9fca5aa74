#include "widgets/PassTimes.h"

namespace wisp {

QString PassTimes::describe() const
{
    return QStringLiteral("upload %1, shadow %2, backdrop %3, hair %4, present %5 ms")
        .arg(uploadMs, 0, 'f', 1)
        .arg(shadowMs, 0, 'f', 1)
        .arg(backdropMs, 0, 'f', 1)
        .arg(hairMs, 0, 'f', 1)
        .arg(presentMs, 0, 'f', 1);
}

void PassClock::start(GlFunctions* gl, bool enabled)
{
    m_gl = enabled ? gl : nullptr;
    if (!m_gl)
        return;
    m_gl->glFinish(); // what came before is not this paint's
    m_last = std::chrono::steady_clock::now();
}

double PassClock::lap()
{
    if (!m_gl)
        return 0.0;
    m_gl->glFinish();
    const auto now = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - m_last).count();
    m_last = now;
    return ms;
}

} // namespace wisp
