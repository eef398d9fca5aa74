#pragma once
// What the viewport shows over its 3D content: the heads-up line and the axis gizmo, painted with
// QPainter (into images, which FrameCompositor draws over each frame).
//
// Thread: GUI.

#include "sim/solver/Frame.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <QImage>
#include <QRectF>
#include <QString>

class QPainter;

namespace wisp {

// "fps 60 · sim 0.12 ms/step · 4582 strands · 7632 particles", then " · slow motion x0.5" when the
// simulation runs slower than real time on purpose, " · falling behind" when it cannot keep up and
// " · preview" while the hair is drawn with less detail (level of detail, see HairDetail), with the
// fraction of strands drawn when that is not all of them: " · preview 40%".
// Paused: "paused · 4582 strands · 7632 particles" (no frame rate or solver time, which would only
// be the last ones measured before the pause).
QString composeHudText(
    const Frame* frame, double framesPerSecond, double drawnFraction = 1.0, bool preview = false, bool paused = false);

// Top-left corner, light text on a translucent dark panel so it reads on any background.
void drawHud(QPainter& painter, const QString& text);

// World X (red), Y (green) and Z (blue) as the camera sees them, in `area` (logical pixels).
// Axes pointing away from the viewer are drawn first and dimmer.
void drawAxisGizmo(QPainter& painter, const QRectF& area, const glm::mat4& view);

// The wind as the camera sees it, in `area` beside the gizmo: an arrow along the wind's direction
// on screen (shorter as it blows toward or away from the viewer) and its speed. Drawn in a corner
// rather than in the scene, so it never covers the head or the hair.
void drawWindIndicator(
    QPainter& painter, const QRectF& area, const glm::mat4& view, const glm::vec3& windMetresPerSecond);

// The same as images, transparent around what they show, `ratio` device pixels per logical pixel.
// The heads-up line's image belongs at the view's top-left corner; the gizmo's (kGizmoImageSize
// logical pixels square, kGizmoImageSize + kWindIndicatorWidth wide with a wind) at its bottom-left
// corner, the wind indicator right of the axes.
QImage paintHudImage(const QString& text, double ratio);
QImage paintGizmoImage(const glm::mat4& view, double ratio, const glm::vec3& windMetresPerSecond = glm::vec3(0.0f));
constexpr int kGizmoImageSize = 92;
constexpr int kWindIndicatorWidth = 84;

} // namespace wisp
