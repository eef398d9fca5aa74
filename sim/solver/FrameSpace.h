#pragma once
// Where a frame puts the head: head space to world space (Frame::headToWorld) and back. The one
// place the brushes (BrushContext) and the editor's tools (PaintTool, StyleTool, on the drawn
// frame) read it.
// Thread safety: any thread; frames are immutable.

#include "sim/solver/Frame.h"

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/mat4x4.hpp>

namespace wisp {

// Identity without a frame (before the first one is published).
inline glm::mat4 headToWorldOf(const FramePtr& frame)
{
    return frame ? frame->headToWorld : glm::mat4(1.0f);
}

inline glm::mat4 worldToHeadOf(const FramePtr& frame)
{
    return glm::affineInverse(headToWorldOf(frame)); // rigid: rotation and translation
}

} // namespace wisp
