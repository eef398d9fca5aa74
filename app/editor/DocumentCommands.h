#pragma once
// One small QUndoCommand per kind of edit (as Tiled does), merged while a slider is dragged.
// Commands name regions by id, not index, so they stay right after reordering.

#include "io/HeadPlacement.h"
#include "sim/geometry/HeadModel.h"
#include "sim/geometry/TriangleMesh.h"
#include "sim/groom/GrowthRegion.h"
#include "sim/motion/HairBake.h"
#include "sim/motion/HeadMotion.h"
#include "sim/params/Parameters.h"
#include "sim/style/StyleEdits.h"

#include <QUndoCommand>

#include <cstdint>
#include <map>
#include <optional>
#include <vector>

namespace wisp {

class Document;

class SetParameterCommand : public QUndoCommand {
public:
    SetParameterCommand(Document* document, Param id, double oldValue, double newValue, bool open);
    void undo() override;
    void redo() override;
    int id() const override { return kMergeIdBase + static_cast<int>(m_param); }
    bool mergeWith(const QUndoCommand* other) override;

    static constexpr int kMergeIdBase = 1000;

private:
    Document* m_document;
    Param m_param;
    double m_old;
    double m_new;
    bool m_open; // the gesture is still going on: the next edit of this parameter merges here
};

// A Wisp-group parameter of one region; merges like SetParameterCommand (same region and parameter).
class SetRegionParameterCommand : public QUndoCommand {
public:
    SetRegionParameterCommand(Document* document, std::uint32_t regionId, const QString& regionName, Param id,
        double oldValue, double newValue, bool open);
    void undo() override;
    void redo() override;
    int id() const override { return kMergeIdBase + static_cast<int>(m_param); }
    bool mergeWith(const QUndoCommand* other) override;

    static constexpr int kMergeIdBase = 2000;

private:
    void updateText();
    Document* m_document;
    std::uint32_t m_region;
    QString m_regionName;
    Param m_param;
    double m_old;
    double m_new;
    bool m_open;
};

// Any change of the region list itself (add, remove, rename, reorder, show, hide, solo, colour):
// the whole list before and after. The lists share their painted weights copy-on-write with the
// document (sim/groom/RegionWeights.h), so a step holds only the region records, not the weights.
class SetRegionsCommand : public QUndoCommand {
public:
    SetRegionsCommand(Document* document, std::vector<GrowthRegion> before, std::uint32_t soloBefore,
        std::vector<GrowthRegion> after, std::uint32_t soloAfter, const QString& text);
    void undo() override;
    void redo() override;

private:
    Document* m_document;
    std::vector<GrowthRegion> m_before, m_after;
    std::uint32_t m_soloBefore, m_soloAfter;
};

// One brush stroke: only the weights it changed. Its first redo is a no-op: the stroke was applied
// live while painting.
class PaintStrokeCommand : public QUndoCommand {
public:
    PaintStrokeCommand(Document* document, std::uint32_t regionId, std::vector<std::uint32_t> vertices,
        std::vector<float> before, std::vector<float> after, const QString& text);
    void undo() override;
    void redo() override;

private:
    Document* m_document;
    std::uint32_t m_region;
    std::vector<std::uint32_t> m_vertices;
    std::vector<float> m_before, m_after;
    bool m_applied = true;
};

// One styling stroke (comb, cut, perm, ...): the strands it changed, before and after. Its first
// redo is a no-op: the stroke was applied live.
class StyleStrokeCommand : public QUndoCommand {
public:
    StyleStrokeCommand(Document* document, std::map<std::uint64_t, std::optional<StrandStyle>> before,
        std::map<std::uint64_t, std::optional<StrandStyle>> after, const QString& text, bool applied);
    void undo() override;
    void redo() override;

private:
    Document* m_document;
    std::map<std::uint64_t, std::optional<StrandStyle>> m_before, m_after;
    bool m_applied;
};

class ReplaceHeadCommand : public QUndoCommand {
public:
    // The heads are shared, not copied: undo and redo swap them without rebuilding their BVHs.
    ReplaceHeadCommand(Document* document, HeadModelPtr oldHead, std::vector<GrowthRegion> oldRegions,
        HeadModelPtr newHead, std::vector<GrowthRegion> newRegions, const QString& name);
    struct Origin {
        QString source;
        io::HeadPlacement placement;
    };
    void setOrigins(Origin before, Origin after);
    void undo() override;
    void redo() override;

private:
    Document* m_document;
    HeadModelPtr m_oldHead, m_newHead;
    std::vector<GrowthRegion> m_oldRegions, m_newRegions;
    Origin m_oldOrigin, m_newOrigin;
};

// A preset applied: every global parameter and every region's look, before and after (the
// regions' weights shared, as in SetRegionsCommand).
class ApplyLookCommand : public QUndoCommand {
public:
    ApplyLookCommand(Document* document, ParameterValues parametersBefore, std::vector<GrowthRegion> regionsBefore,
        ParameterValues parametersAfter, std::vector<GrowthRegion> regionsAfter, const QString& text);
    void undo() override;
    void redo() override;

private:
    Document* m_document;
    ParameterValues m_parametersBefore, m_parametersAfter;
    std::vector<GrowthRegion> m_regionsBefore, m_regionsAfter;
};

// The head's motion (keys and procedural motion), before and after.
class SetHeadMotionCommand : public QUndoCommand {
public:
    SetHeadMotionCommand(Document* document, HeadMotion before, HeadMotion after, const QString& text);
    void undo() override;
    void redo() override;

private:
    Document* m_document;
    HeadMotion m_before, m_after;
};

// The timeline's frame range and fps, before and after.
class SetTimelineCommand : public QUndoCommand {
public:
    SetTimelineCommand(Document* document, BakeRange before, BakeRange after, const QString& text);
    void undo() override;
    void redo() override;

private:
    Document* m_document;
    BakeRange m_before, m_after;
};

} // namespace wisp
