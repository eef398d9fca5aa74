#pragma once
// The growth brush: paints the current region's mask on the head under the cursor, as sculpting
// and texture-painting tools do.
//   left drag                   paint (add)
//   Ctrl + left drag            erase (hold Ctrl to erase, as Blender's brushes invert)
//   Shift + left drag           smooth
//   [ and ]                     smaller and larger brush
// The surface under the cursor is found by a ray cast through the head's BVH (the document's
// HeadModel, built once per head), so it stays
// interactive on a 270k-triangle head. X-mirror symmetry is on by default. While the tool is
// active, Alt + drag and the middle button still move the camera (the viewport handles those).
//
// The tool is an event filter on the viewport: the viewport itself knows nothing of painting.
//
// Thread: GUI.

#include "app/editor/ViewportBrush.h"
#include "sim/geometry/HeadModel.h"
#include "sim/groom/ScalpBrush.h"
#include "widgets/GuideGeometry.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <QObject>
#include <QPointF>

class QKeyEvent;

#include <memory>
#include <optional>

namespace wisp {

class Document;
class Viewport;

class PaintTool : public ViewportBrush {
    Q_OBJECT
public:
    PaintTool(Document* document, Viewport* viewport, QObject* parent = nullptr);
    ~PaintTool() override;

    bool isActive() const { return m_active; }
    const BrushSettings& settings() const { return m_settings; }
    float mirrorPlaneX() const;

    // Where the cursor's ray meets the head as the viewport draws it (the styling tools use it too):
    // head space, where the scalp is painted; the ray is taken into head space by the drawn frame's
    // transform, so a turned or moved head is painted where it is seen.
    struct Hit {
        glm::vec3 point; // head space, metres
        glm::vec3 normal; // unit, head space, facing the camera
    };
    std::optional<Hit> hitAt(QPointF widgetPosition) const;
    // `cursor` at a head point with its normal (head space), and its mirror across the head's plane,
    // placed in the world where the head is drawn.
    void placeCursor(BrushCursor& cursor, const glm::vec3& point_hs, const glm::vec3& normal_hs) const;
    // [ and ] make the brush smaller and larger, for every tool that shares these settings; true
    // when `e` was one of them.
    bool resizeByKey(const QKeyEvent* e);

public slots:
    void setActive(bool active);
    void setRadius(double metres);
    void setStrength(double strength);
    void setFalloff(double falloff);
    void setMode(wisp::BrushMode mode);
    void setMirror(bool mirror);

signals:
    void activeChanged(bool active);
    void settingsChanged();

protected:
    bool brushEnabled() const override { return m_active; }
    bool beginStroke(QPointF position, Qt::KeyboardModifiers modifiers) override;
    void continueStroke(QPointF position, Qt::KeyboardModifiers modifiers) override;
    void finishStroke(QPointF position, Qt::KeyboardModifiers modifiers) override;
    void showCursor(QPointF position, Qt::KeyboardModifiers modifiers) override;
    bool keyPressed(const QKeyEvent* event) override { return resizeByKey(event); }

private:
    BrushMode modeFor(Qt::KeyboardModifiers modifiers) const;
    void dabAlong(const Hit& to, Qt::KeyboardModifiers modifiers);
    void endStroke();

    Document* m_document;
    BrushSettings m_settings;
    bool m_active = false;
    std::optional<glm::vec3> m_lastDab; // of the stroke going on
};

} // namespace wisp
