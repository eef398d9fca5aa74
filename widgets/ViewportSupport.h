#pragma once
// What Viewport's source files share (Viewport.cpp, ViewportCamera.cpp, ViewportFrames.cpp,
// ViewportGl.cpp): the backdrop's colours, the surface format and a bounds check. Internal to
// widgets/.

#include "sim/geometry/TriangleMesh.h"

#include <glm/vec3.hpp>

#include <QSurfaceFormat>

#include <cmath>

namespace wisp {

inline const glm::vec3 kBackgroundTop{ 0.235f, 0.247f, 0.275f }; // sRGB
inline const glm::vec3 kBackgroundBottom{ 0.105f, 0.110f, 0.125f };

inline bool finiteBounds(const Aabb& b)
{
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(b.min[i]) || !std::isfinite(b.max[i]) || b.min[i] > b.max[i])
            return false;
    return true;
}

// The context's and the window's: the window only receives finished frames, so it needs neither
// depth nor samples (the frame's own framebuffers have them, see GlCanvas).
QSurfaceFormat viewportFormat();

} // namespace wisp
