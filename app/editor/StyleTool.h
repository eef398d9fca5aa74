#pragma once
// The salon brushes on the viewport (Lee et al.'s cut, comb and perm; Ward et al.'s wet hair,
// hairspray and blow-dryer). One tool at a time; each is a brush with the growth brush's radius,
// strength, falloff and X-mirror (BrushPanel), and each stroke is one undo step
// (Document::beginStyleStroke). What each brush does is its operation's (sim/style/); this tool only
// turns mouse events into an operation's begin, step and end, and passes on what they return: the
// stroke's edits to the document, held strands, wet wisps and dryers to the simulation host.
//   comb        left drag: the strands under the cursor follow the stroke and rest where left
//   cut         left drag across the hair: every strand the stroke crosses is cut where it crosses
//   length      left drag: grows the strands under the cursor; Ctrl + drag shrinks them
//   curl        left drag: perms the touched wisps with the curl set in the panel; Ctrl takes it out
//   wet         left drag: wets the touched wisps; Ctrl towel-dries
//   hairspray   left drag: the touched wisps hold their current shape; Ctrl washes the spray out
//   blow-dry    hold the left button: a cone of air from the cursor along the view
// The brush ring sits on the head under the cursor. [ and ] change the radius, as for painting;
// Alt + drag and the middle button still move the camera.
//
// Thread: GUI.

#include "app/editor/StyleBrushText.h"
#include "app/editor/ViewportBrush.h"
#include "sim/style/HairDryer.h"
#include "sim/style/StyleOperation.h"

#include <QObject>
#include <QPointF>

#include <memory>
#include <optional>
#include <vector>

namespace wisp {

class Document;
class PaintTool;
class SimulationHost;
class Viewport;

class StyleTool : public ViewportBrush {
    Q_OBJECT
public:
    // `brushSettings` lends its radius, strength, falloff and mirror.
    StyleTool(Document* document, Viewport* viewport, SimulationHost* simulation, PaintTool* brushSettings,
        QObject* parent = nullptr);
    ~StyleTool() override;

    std::optional<StyleBrush> brush() const { return m_brush; }
    bool isActive() const { return m_brush.has_value(); }
    float curlRadiusMetres() const { return m_curlRadius; }
    float curlTurnsPerMetre() const { return m_curlTurns; }
    // The blow-dryers blowing now (while the button is held; two with X symmetry).
    const std::vector<HairDryer>& dryers() const { return m_dryers; }

public slots:
    void setBrush(std::optional<wisp::StyleBrush> brush); // nullopt: no styling tool
    void setCurlRadiusMetres(double metres);
    void setCurlTurnsPerMetre(double turns);

signals:
    void brushChanged(std::optional<wisp::StyleBrush> brush);
    void curlChanged();
    void message(const QString& text);

protected:
    bool brushEnabled() const override { return m_brush.has_value(); }
    bool beginStroke(QPointF position, Qt::KeyboardModifiers modifiers) override;
    void continueStroke(QPointF position, Qt::KeyboardModifiers modifiers) override;
    void finishStroke(QPointF position, Qt::KeyboardModifiers modifiers) override;
    void showCursor(QPointF position, Qt::KeyboardModifiers modifiers) override;
    bool keyPressed(const QKeyEvent* event) override;

private:
    BrushContext context() const;
    BrushSample sampleAt(QPointF widgetPosition, Qt::KeyboardModifiers modifiers) const;
    void drag(QPointF position, Qt::KeyboardModifiers modifiers);
    void end();
    void cancel();
    void passOn(const StyleEffects& effects);
    void report(int changedStrands);
    QString brushName() const { return styleBrushName(m_brush.value_or(StyleBrush::Comb)); }

    Document* m_document;
    SimulationHost* m_simulation;
    PaintTool* m_brushSettings;
    std::optional<StyleBrush> m_brush;
    float m_curlRadius = 0.01f;
    float m_curlTurns = 10.0f;

    std::unique_ptr<StyleOperation> m_operation; // of the stroke going on
    QPointF m_lastPosition; // of its last sample
    std::vector<HairDryer> m_dryers;
};

} // namespace wisp
