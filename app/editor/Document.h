#pragma once
// What the artist is editing: the head, its growth regions (painted masks with their own wisp
// parameters) and every global parameter. It changes only through undoable commands on its
// QUndoStack, so every edit can be undone and one gesture (a slider drag, a brush stroke) is one step.
//
// Thread: GUI.

#include "io/HeadPlacement.h"
#include "io/PresetFile.h"
#include "io/ProjectFile.h"
#include "sim/geometry/HeadModel.h"
#include "sim/geometry/TriangleMesh.h"
#include "sim/groom/GrowthRegion.h"
#include "sim/motion/HairBake.h"
#include "sim/motion/HeadMotion.h"
#include "sim/params/Parameters.h"
#include "sim/style/StyleEdits.h"

#include <QObject>
#include <QString>
#include <QUndoStack>

#include <cstdint>
#include <map>
#include <optional>
#include <vector>

namespace wisp {

class Document : public QObject {
    Q_OBJECT
public:
    // Starts on the built-in head with one region ("Scalp") painted with its default growth map.
    explicit Document(QObject* parent = nullptr);

    const TriangleMesh& head() const { return m_head->mesh(); }
    // The head with its BVH and brush grid, built once per head and shared (brushes, simulation).
    const HeadModelPtr& headModel() const { return m_head; }
    const ParameterValues& parameters() const { return m_parameters; }
    QUndoStack* undoStack() { return &m_undoStack; }

    // --- Regions -------------------------------------------------------------------------------
    const std::vector<GrowthRegion>& regions() const { return m_regions; }
    int regionCount() const { return static_cast<int>(m_regions.size()); }
    const GrowthRegion& region(int index) const { return m_regions[static_cast<std::size_t>(index)]; }
    int indexOfRegion(std::uint32_t id) const; // -1 if none has it
    std::uint32_t soloRegion() const { return m_soloId; } // kNoSolo when none is solo'd

    // The region the wisp panel edits and the brush paints (selection: not an edit, not undoable).
    // -1 only when there is no region.
    int currentRegion() const { return m_current; }
    void setCurrentRegion(int index);

    // --- Edits, each one undo step ---------------------------------------------------------------
    // The artist's edit of one global parameter. While `dragging`, successive edits of the same
    // parameter merge into one step; the edit with dragging == false closes it. Returns the refusal
    // message for an invalid value (nothing is pushed then).
    QString editParameter(Param id, double value, bool dragging);
    // The same for a Wisp-group parameter of one region.
    QString editRegionParameter(int index, Param id, double value, bool dragging);

    // Adds a region with default wisp parameters and an empty mask after the others; it becomes
    // the current region. Returns its index.
    int addRegion(const QString& name);
    void removeRegion(int index);
    void renameRegion(int index, const QString& name); // an empty name is refused (nothing pushed)
    void moveRegion(int from, int to);
    void setRegionVisible(int index, bool visible);
    void setSoloRegion(std::uint32_t id); // kNoSolo ends solo
    void setRegionColours(int index, const glm::vec3& root, const glm::vec3& tip);

    // A brush stroke on the current region's mask: begin, any number of live updates (the hair
    // follows each), end. The whole stroke is one undo step holding only the weights it changed.
    // A stroke that changed nothing leaves no step.
    void beginStroke();
    std::vector<float>& strokeWeights(); // the current region's weights, to change during a stroke
    void strokeUpdated(); // after changing them: emits regionWeightsChanged
    void endStroke(const QString& text);
    bool inStroke() const { return m_strokeRegion >= 0; }

    // --- Salon edits (styling on live hair; sim/style/StyleEdits.h) -----------------------------------
    // Per strand: cut length, perm, hairspray, wetness, combed shape. Presets never touch them.
    const StyleEditsPtr& style() const { return m_style; }
    // A styling stroke, like a paint stroke: begin, change strokeStyle() and call
    // styleStrokeUpdated() after each change (the hair follows), end. The whole stroke is one undo
    // step holding only the strands it changed; a stroke that changed nothing leaves none.
    void beginStyleStroke();
    StyleEdits& strokeStyle();
    void styleStrokeUpdated(); // emits styleChanged
    int endStyleStroke(const QString& text); // returns how many strands the stroke changed
    bool inStyleStroke() const { return m_styleStroke.has_value(); }

    // Replaces the head as one undo step; its regions start over as one region grown where
    // `growthWeights` say. `source` is the file it came from (empty: built in) and `placement`
    // how it was brought to metres, +Y up and centred (io/HeadPlacement.h).
    void replaceHead(TriangleMesh head, std::vector<float> growthWeights, const QString& name,
        const QString& source = {}, const io::HeadPlacement& placement = {});

    // Applies a preset as one undo step: every global parameter, and each region's wisp
    // parameters and colours from the preset's region of the same index (regions beyond the
    // preset's take its last region). Painted weights and the head stay.
    void applyPreset(const io::Preset& preset);
    // The current look as a preset (no head, no weights).
    io::Preset toPreset(const QString& name) const;

    // Adds a region of imported strands (head space, metres) as one undo step; it becomes current.
    int addImportedHair(std::shared_ptr<const HairCurves> strands, const QString& name);

    // --- Head motion and timeline (sim/motion/) -------------------------------------------------
    // The head's keyframes and procedural motion, and the timeline's frame range and fps. Saved in
    // projects; each change is one undo step (`text` names it in the Edit menu).
    const HeadMotion& headMotion() const { return m_motion; }
    const BakeRange& timeline() const { return m_timeline; }
    // Returns the refusal message for an invalid motion or range (nothing is pushed then).
    QString setHeadMotion(HeadMotion motion, const QString& text);
    QString setTimeline(const BakeRange& range, const QString& text);
    // --- Projects --------------------------------------------------------------------------------
    const QString& headSource() const { return m_headSource; }
    const io::HeadPlacement& headPlacement() const { return m_headPlacement; }
    // Everything but the camera (the caller fills it in).
    io::Project toProject() const;
    // Replaces the whole document with a project's (not undoable: the undo history starts over).
    void loadProject(io::Project project);
    // Back to the built-in head and hairstyle, history cleared.
    void reset();

    // --- For commands only: apply without touching the undo stack -------------------------------
    void applyParameter(Param id, double value);
    void applyRegionParameter(std::uint32_t regionId, Param id, double value);
    void applyRegions(std::vector<GrowthRegion> regions, std::uint32_t soloId); // structure changes
    void applyRegionWeights(
        std::uint32_t regionId, const std::vector<std::uint32_t>& vertices, const std::vector<float>& values);
    void applyHead(HeadModelPtr head, std::vector<GrowthRegion> regions);
    void applyHeadOrigin(const QString& source, const io::HeadPlacement& placement);
    void applyLook(const ParameterValues& parameters, std::vector<GrowthRegion> regions); // presets
    // Per strand identity, the style it gets (nullopt: no edit).
    using StyleChanges = std::map<std::uint64_t, std::optional<StrandStyle>>;
    void applyStyleChanges(const StyleChanges& changes);
    void applyHeadMotion(const HeadMotion& motion);
    void applyTimeline(const BakeRange& range);
    std::uint32_t nextRegionId() const;

signals:
    void parameterChanged(wisp::Param id);
    void parametersReplaced(); // every global parameter may have changed (preset, project)
    void headChanged(); // head and all regions replaced
    void regionsChanged(); // added, removed, renamed, reordered, shown, hidden, solo'd, recoloured
    void regionParameterChanged(int index, wisp::Param id);
    void regionWeightsChanged(std::uint32_t regionId);
    void currentRegionChanged(int index);
    void headMotionChanged(); // keys or procedural motion changed (an edit, undo, a project)
    void timelineChanged(); // frame range or fps changed
    void styleChanged(); // the salon edits changed

private:
    HeadModelPtr m_head; // never null
    QString m_headSource;
    io::HeadPlacement m_headPlacement;
    HeadMotion m_motion;
    BakeRange m_timeline;
    ParameterValues m_parameters;
    std::vector<GrowthRegion> m_regions;
    std::uint32_t m_soloId = kNoSolo;
    int m_current = -1;
    int m_strokeRegion = -1;
    RegionWeights m_strokeBefore; // shares the weights until the stroke first writes
    StyleEditsPtr m_style = std::make_shared<const StyleEdits>();
    std::optional<StyleEdits> m_styleStroke; // the edits being changed by a styling stroke
    StyleEditsPtr m_styleBefore; // and as they were when it began
    QUndoStack m_undoStack;
};

} // namespace wisp
