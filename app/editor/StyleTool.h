#pragma once
// The salon brushes, working on the hair while it simulates (Lee et al.'s cut, comb and perm; Ward
// et al.'s wet hair, hairspray and blow-dryer). One tool at a time; each is a brush with the
// growth brush's radius, strength, falloff and X-mirror (BrushPanel), and each stroke is one undo
// step (Document::beginStyleStroke):
//   comb        left drag: drags the strands under the cursor along the stroke, then makes the
//               combed shape where they rest (the simulation solves the rest shape that sags onto it)
//   cut         left drag across the hair: every strand the stroke crosses is cut where it crosses
//   length      left drag: grows the strands under the cursor; Ctrl + drag shrinks them
//   curl        left drag: perms the touched wisps with the curl radius and turns set in the panel;
//               Ctrl + drag takes the perm out
//   wet         left drag: wets the touched wisps (heavier, clumped, curls relaxed); Ctrl: towel-dries
//   hairspray   left drag: the touched wisps hold their current shape, stiffer by the strength;
//               Ctrl + drag washes the spray out
//   blow-dry    hold the left button: a cone of air from the cursor along the view pushes and dries
//               the hair; what it dried is one undo step when released
// The brush ring sits on the head under the cursor. [ and ] change the radius, as for painting;
// Alt + drag and the middle button still move the camera.
//
// The tool is an event filter on the viewport, reads the hair from the newest frame of the
// simulation host and changes only the document (and, live, the host's held strands and dryer).
//
// Thread: GUI.

#include "app/editor/ViewportBrush.h"
#include "sim/HairDryer.h"
#include "sim/StyleEdits.h"

#include <glm/vec3.hpp>

#include <QObject>
#include <QPointF>

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <vector>

namespace wisp {

class Document;
class PaintTool;
class SimulationHost;
class Viewport;
struct ViewRay;

enum class StyleBrush { Comb, Cut, Length, Curl, Wet, Hairspray, BlowDry };

// A brush's name (menus, the panel, its strokes' undo text) and how it is used, one line (the
// panel's hint and the actions' tooltips).
QString styleBrushName(StyleBrush brush);
QString styleBrushHelp(StyleBrush brush);

class StyleTool : public ViewportBrush {
    Q_OBJECT
public:
    // `brushSettings` lends its radius, strength, falloff, mirror and head picking.
    StyleTool(Document* document, Viewport* viewport, SimulationHost* simulation, PaintTool* brushSettings,
              QObject* parent = nullptr);

    std::optional<StyleBrush> brush() const { return m_brush; }
    bool isActive() const { return m_brush.has_value(); }
    float curlRadiusMetres() const { return m_curlRadius; }
    float curlTurnsPerMetre() const { return m_curlTurns; }
    // The blow-dryers blowing now (while the button is held; two with X symmetry).
    const std::vector<HairDryer>& dryers() const { return m_dryers; }

    // The length brush changes a strand by this share of its length per dab at full strength.
    static constexpr float kLengthStepShare = 0.06f;
    // Hairspray at full strength multiplies the stiffness by 1 + this per stroke.
    static constexpr float kSprayStiffening = 9.0f;
    // The dryer's nozzle is this far in front of the hair under the cursor.
    static constexpr float kDryerDistanceMetres = 0.12f;

public slots:
    void setBrush(std::optional<wisp::StyleBrush> brush);  // nullopt: no styling tool
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
    struct Grabbed {  // a strand the comb holds
        std::uint64_t identity = 0;
        float weight = 0.0f;
        float depth = 0.0f;
        bool mirrored = false;
        std::vector<glm::vec3> positions;
        std::vector<float> segmentLengths;
    };
    struct Ray {
        glm::vec3 origin;
        glm::vec3 direction;
        float maxDepth;  // the head's surface along it, or far
    };

    std::vector<Ray> raysAt(QPointF widgetPosition) const;  // the cursor's, and its mirror when on
    void drag(QPointF position, Qt::KeyboardModifiers modifiers);
    void end();
    void cancel();

    void grabForComb(QPointF position);
    void combTo(QPointF position);
    void cutBetween(QPointF from, QPointF to);
    void dab(QPointF position, Qt::KeyboardModifiers modifiers);
    HairDryer dryerAt(QPointF position) const;
    void placeDryer(QPointF position);
    void keepDriedWetness();
    float lengthOf(std::uint64_t identity, std::uint32_t strand) const;
    void report(int changedStrands);
    QString brushName() const { return styleBrushName(m_brush.value_or(StyleBrush::Comb)); }

    Document* m_document;
    SimulationHost* m_simulation;
    PaintTool* m_brushSettings;
    std::optional<StyleBrush> m_brush;
    float m_curlRadius = 0.01f;
    float m_curlTurns = 10.0f;

    QPointF m_lastPosition;
    std::vector<Grabbed> m_grabbed;
    int m_combedStrands = 0;  // drawn strands the comb's stroke moves (the caught wisps')
    std::set<std::uint64_t> m_touched;  // strands this stroke already changed (spray, perm: once)
    std::vector<HairDryer> m_dryers;
    std::map<std::uint64_t, float> m_wetBefore;  // the blow-dry stroke: applied wetness as it began
};

}  // namespace wisp
