// Style edits and files: edits come back with the project, presets leave them, a stroke never
// leaves an edit the project file would refuse, and a cut under a curly preset stays inside.
#include "StylingTestSupport.h"

using namespace wisp;
using namespace wisp::test;

namespace {

TEST_F(StylingTest, EditsComeBackWithTheProjectAndPresetsLeaveThem)
{
    look(90.0f, { box.center().x, box.center().y - 0.08f, box.center().z });
    pick(Qt::Key_X, StyleBrush::Cut);
    stroke({ { box.max.x + 0.05f, box.center().y - 0.08f, box.max.z },
               { box.max.x + 0.05f, box.center().y - 0.08f, box.min.z } },
        Qt::NoModifier, 16);
    pick(Qt::Key_P, StyleBrush::Curl);
    stroke({ rightSide(0.0f, 0.05f) + glm::vec3(0.03f, 0, 0), rightSide(0.0f, -0.05f) + glm::vec3(0.03f, 0, 0) });
    const StyleEdits styled = *document()->style();
    ASSERT_GT(styled.size(), 10u);
    const Strands rest = byIdentity(frame(), true);

    // A preset changes the look's parameters, never the salon edits.
    io::Preset preset = document()->toPreset(QStringLiteral("Same"));
    preset.parameters.set(Param::Gravity, 5.0);
    document()->applyPreset(preset);
    settle();
    EXPECT_EQ(*document()->style(), styled);

    // Saved, a new project (no edits), opened again: the edits and the groom they make are back.
    window->fileMenu()->setInteractive(false);
    ProjectController* projects = window->fileMenu()->projects();
    QTemporaryDir dir;
    const QString path = dir.filePath(QStringLiteral("styled.wisp"));
    ASSERT_TRUE(projects->saveAs(path)) << projects->lastError().toStdString();
    ASSERT_TRUE(settleNewGroom([&] { return projects->newProject(); }));
    EXPECT_TRUE(document()->style()->empty());
    ASSERT_TRUE(settleNewGroom([&] { return projects->open(path); })) << projects->lastError().toStdString();
    EXPECT_EQ(*document()->style(), styled);
    // The same density as the saved groom: compare the styled strands' rest shapes.
    const Strands reopened = byIdentity(frame(), true);
    int compared = 0;
    for (const auto& [id, style] : styled)
        if (reopened.count(id) && rest.count(id)) {
            EXPECT_EQ(strandLength(reopened.at(id)), strandLength(rest.at(id))) << id;
            ++compared;
        }
    EXPECT_EQ(compared, static_cast<int>(styled.size()));
    document()->undoStack()->setClean();
}

TEST_F(StylingTest, AStrokeNeverLeavesAnEditTheProjectFileWouldRefuse)
{
    const std::uint64_t id = frame()->groomShape->identities[0];
    document()->beginStyleStroke();
    document()->strokeStyle()[id].wetness = 3.0f; // what no tool should make
    document()->strokeStyle()[id + 1].lengthMetres = 0.1f;
    document()->styleStrokeUpdated();
    EXPECT_EQ(document()->endStyleStroke(QStringLiteral("Test")), 1);
    EXPECT_EQ(document()->style()->count(id), 0u);
    ASSERT_EQ(document()->style()->count(id + 1), 1u);
    EXPECT_EQ(document()->style()->at(id + 1).lengthMetres, 0.1f);
    io::Project project = document()->toProject();
    QTemporaryDir dir;
    EXPECT_TRUE(io::writeProject(dir.filePath(QStringLiteral("ok.wisp")).toStdString(), project));
    document()->undoStack()->setClean();
}

// Issue 11: after File ▸ New, a cut at eyebrow height and the bundled Curly preset (more segments,
// another density and wisp size) applied from the preset browser, no strand may stick out: every
// drawn strand hangs under gravity within its length of its root, and keeps the length its edit
// (or its groom) gives it.
TEST_F(StylingTest, CutThenCurlyPresetLeavesNoStrandStickingOut)
{
    window->fileMenu()->setInteractive(false);
    SimulationHost* host = window->simulation();
    // File ▸ New, by its shortcut: the default groom.
    const std::uint64_t groomBefore = frame()->groomVersion;
    QTest::keyClick(window->viewport(), Qt::Key_N, Qt::ControlModifier);
    ASSERT_TRUE(wisp::test::waitUntil([&] { return frame()->groomVersion > groomBefore; }));
    settle();
    ASSERT_FALSE(host->isPlaying());
    runSteps(150); // hanging

    // The cut: from the front, a horizontal stroke across the face at eyebrow height (the brow
    // ridge of the built-in head), both sides (X symmetry).
    const float browY = box.min.y + 0.62f * box.size().y;
    look(0.0f, { box.center().x, browY, box.center().z }, 0.6f);
    pick(Qt::Key_X, StyleBrush::Cut);
    const float zFront = box.max.z + 0.03f;
    stroke({ { box.min.x - 0.04f, browY, zFront }, { box.max.x + 0.04f, browY, zFront } }, Qt::NoModifier, 24);
    const StyleEdits cut = *document()->style();
    ASSERT_GT(cut.size(), 20u) << "the stroke cut almost nothing: the test proves nothing";

    // Presets ▸ Curly ▸ Apply, in the dock.
    auto* dock = window->findChild<QDockWidget*>(QStringLiteral("presetsDock"));
    ASSERT_NE(dock, nullptr);
    dock->show();
    dock->raise();
    QTest::qWait(50);
    QListWidget* list = window->presetBrowser()->listWidget();
    int row = -1;
    for (int r = 0; r < list->count(); ++r)
        if (list->item(r)->text() == QStringLiteral("Curly"))
            row = r;
    ASSERT_GE(row, 0);
    list->scrollToItem(list->item(row));
    const QRect rect = list->visualItemRect(list->item(row));
    ASSERT_FALSE(rect.isEmpty());
    QTest::mouseClick(list->viewport(), Qt::LeftButton, Qt::NoModifier, rect.center());
    ASSERT_EQ(list->currentRow(), row);
    ASSERT_TRUE(window->presetBrowser()->applyButton()->isEnabled());
    QTest::mouseClick(window->presetBrowser()->applyButton(), Qt::LeftButton);
    settle();
    ASSERT_EQ(document()->parameters().getInt(Param::Segments), 48) << "the Curly preset was not applied";
    EXPECT_EQ(*document()->style(), cut) << "a preset leaves the salon edits";
    ASSERT_EQ(frame()->strands.strand(0).size(), 49u);
    runSteps(120);

    const FramePtr f = frame();
    const GroomShape& g = *f->groomShape;
    const HairCurves& drawn = f->strands;
    ASSERT_EQ(drawn.strandCount(), g.lengths.size());
    int tooFar = 0, standing = 0, wrongLength = 0, keysMeasured = 0, cutKeys = 0;
    float worstReach = 0.0f, worstRise = 0.0f;
    for (std::size_t i = 0; i < drawn.strandCount(); ++i) {
        const auto s = drawn.strand(i);
        const std::uint32_t key = g.keyOfWisp[g.wispOf[i]];
        // A member rides beside its key: its points are within its length plus twice its root's
        // offset from the key's root (the offset turned with the key, then clumped) of its root.
        const float offset = i == key ? 0.0f : glm::distance(s.front(), drawn.strand(key).front());
        const float allowed = 1.01f * g.lengths[i] + 2.0f * offset + 1e-4f;
        float reach = 0.0f;
        for (const glm::vec3& p : s)
            reach = std::max(reach, glm::distance(p, s.front()));
        if (reach > allowed) {
            if (tooFar < 5)
                ADD_FAILURE() << "strand " << i << " (length " << g.lengths[i] << ") reaches " << reach
                              << " m from its root";
            ++tooFar;
        }
        worstReach = std::max(worstReach, reach - allowed);
        // Hanging under gravity: a strand longer than 8 cm ends no higher than where it grows (give
        // or take the spring of curls parted at the crown: 4 cm); one standing out from the scalp
        // ends most of its length above it.
        const float rise = s.back().y - s.front().y;
        if (g.lengths[i] > 0.08f && rise > 0.04f) {
            if (standing < 5)
                ADD_FAILURE() << "strand " << i << " (length " << g.lengths[i] << ") ends " << rise
                              << " m above its root: it sticks out";
            ++standing;
        }
        worstRise = std::max(worstRise, g.lengths[i] > 0.08f ? rise : 0.0f);
        if (i == key) {
            // Simulated, so inextensible: drawn as long as its rest shape. That is as long as its
            // groom says, or less (a polyline round a helix whose radius ramps up from the root),
            // but no shorter than the helix's axis: 1 / sqrt(1 + (2 pi r T)^2) = 0.66 of it for Curly.
            ++keysMeasured;
            const float restLength = strandLength(g.rest.strand(i));
            if (std::abs(strandLength(s) - restLength) > 0.01f * restLength + 1e-4f
                || restLength > g.lengths[i] * 1.001f || restLength < 0.65f * g.lengths[i]) {
                ++wrongLength;
            }
            const auto edit = cut.find(g.identities[i]);
            if (edit != cut.end() && edit->second.lengthMetres > 0.0f) {
                EXPECT_FLOAT_EQ(g.lengths[i], edit->second.lengthMetres) << "cut key " << i;
                ++cutKeys;
            }
        }
        // No member is longer than its key by more than the groom's length variation allows.
        if (i != key) {
            EXPECT_LE(g.lengths[i], g.lengths[key] * 1.5f + 1e-4f)
                << "member " << i << " of a key " << g.lengths[key] << " long";
        }
    }
    EXPECT_EQ(tooFar, 0) << "worst by " << worstReach << " m";
    EXPECT_EQ(standing, 0) << "worst rise " << worstRise << " m";
    EXPECT_EQ(wrongLength, 0) << "of " << keysMeasured << " keys";
    EXPECT_GT(cutKeys, 0) << "no cut key hair after the preset: the test proves nothing";
    document()->undoStack()->setClean();
}

} // namespace
