// Undo steps share the regions' painted weights instead of copying them (sim/groom/RegionWeights.h):
// a rename, a preset and a new head keep every untouched region's weights as the very same buffer,
// a paint stroke copies only the region it paints, and no snapshot ever changes.
#include "app/editor/Document.h"
#include "io/PresetFile.h"
#include "sim/geometry/DefaultHead.h"

#include <QUndoStack>

#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

namespace wisp {
namespace {

TEST(DocumentSharing, RenameSharesEveryRegionsWeightsAndUndoBringsBackTheSameBuffers)
{
    Document doc;
    ASSERT_EQ(doc.addRegion("Fringe"), 1);
    const RegionWeights scalp = doc.region(0).weights;
    const RegionWeights fringe = doc.region(1).weights;
    const std::size_t vertices = doc.head().positions.size();
    ASSERT_EQ(scalp.size(), vertices);
    const long scalpHolders = scalp.holderCount();

    doc.renameRegion(0, "Crown");
    ASSERT_EQ(doc.region(0).name, "Crown");
    EXPECT_TRUE(doc.region(0).weights.sharesBufferWith(scalp));
    EXPECT_TRUE(doc.region(1).weights.sharesBufferWith(fringe));
    // The step holds the list before and after: two more holders of one buffer, no copy.
    EXPECT_EQ(scalp.holderCount(), scalpHolders + 2);

    doc.undoStack()->undo();
    EXPECT_EQ(doc.region(0).name, "Scalp");
    EXPECT_TRUE(doc.region(0).weights.sharesBufferWith(scalp));
    doc.undoStack()->redo();
    EXPECT_TRUE(doc.region(0).weights.sharesBufferWith(scalp));

    // Before the weights were shared, each rename copied every region's weights twice.
    std::printf("[ figures  ] default head: %zu vertices; a rename of 2 regions used to copy %zu bytes of weights, "
                "now 0\n",
        vertices, 2 * 2 * vertices * sizeof(float));
}

TEST(DocumentSharing, PresetAndItsUndoKeepTheWeightsBuffers)
{
    Document doc;
    doc.addRegion("Fringe");
    const RegionWeights scalp = doc.region(0).weights;
    const RegionWeights fringe = doc.region(1).weights;
    io::Preset preset;
    preset.name = "Curly";
    preset.parameters = doc.parameters();
    io::RegionLook look;
    look.rootColour = { 0.9f, 0.1f, 0.1f };
    preset.regions.push_back(look);

    doc.applyPreset(preset);
    ASSERT_EQ(doc.region(1).rootColour, look.rootColour);
    EXPECT_TRUE(doc.region(0).weights.sharesBufferWith(scalp));
    EXPECT_TRUE(doc.region(1).weights.sharesBufferWith(fringe));
    doc.undoStack()->undo();
    EXPECT_NE(doc.region(1).rootColour, look.rootColour);
    EXPECT_TRUE(doc.region(0).weights.sharesBufferWith(scalp));
    EXPECT_TRUE(doc.region(1).weights.sharesBufferWith(fringe));
}

TEST(DocumentSharing, AStrokeCopiesOnlyThePaintedRegionAndLeavesEverySnapshotAsItWas)
{
    Document doc;
    doc.addRegion("Fringe"); // current, all zero
    doc.renameRegion(1, "Bangs"); // a step whose snapshots share both regions' weights
    const RegionWeights scalp = doc.region(0).weights;
    const RegionWeights fringeBefore = doc.region(1).weights;

    doc.beginStroke();
    std::vector<float>& weights = doc.strokeWeights();
    ASSERT_EQ(weights.size(), doc.head().positions.size());
    weights[7] = 0.75f;
    doc.strokeUpdated();
    doc.endStroke("Paint");

    EXPECT_EQ(doc.region(1).weights[7], 0.75f);
    EXPECT_FALSE(doc.region(1).weights.sharesBufferWith(fringeBefore));
    EXPECT_EQ(fringeBefore[7], 0.0f); // the rename's snapshot did not see the stroke
    EXPECT_TRUE(doc.region(0).weights.sharesBufferWith(scalp));

    doc.undoStack()->undo(); // the stroke
    EXPECT_EQ(doc.region(1).weights[7], 0.0f);
    doc.undoStack()->redo();
    EXPECT_EQ(doc.region(1).weights[7], 0.75f);
    doc.undoStack()->undo();
    doc.undoStack()->undo(); // the rename: the list as it was, weights and all
    EXPECT_EQ(doc.region(1).name, "Fringe");
    EXPECT_TRUE(doc.region(1).weights.sharesBufferWith(fringeBefore));
    EXPECT_EQ(doc.region(1).weights[7], 0.0f);
}

TEST(DocumentSharing, NewHeadAndItsUndoKeepTheOldRegionsWeights)
{
    Document doc;
    const RegionWeights scalp = doc.region(0).weights;
    DefaultHead other = makeDefaultHead();
    other.growthWeights.assign(other.growthWeights.size(), 1.0f);
    doc.replaceHead(std::move(other.mesh), std::move(other.growthWeights), "Other");
    ASSERT_FALSE(doc.region(0).weights.sharesBufferWith(scalp));
    EXPECT_EQ(doc.region(0).weights[0], 1.0f);
    doc.undoStack()->undo();
    EXPECT_TRUE(doc.region(0).weights.sharesBufferWith(scalp));
}

} // namespace
} // namespace wisp
