// Growth-region weights shared copy-on-write (sim/groom/RegionWeights.h): copies share one buffer,
// the first write to a shared buffer copies it, and a copy taken before never changes.
#include "sim/groom/RegionWeights.h"
#include "sim/groom/GrowthRegion.h"

#include <gtest/gtest.h>

#include <vector>

namespace wisp {
namespace {

TEST(RegionWeights, CopiesShareOneBufferUntilOneWrites)
{
    RegionWeights a = std::vector<float>{ 0.0f, 0.5f, 1.0f };
    const float* buffer = a.data();
    RegionWeights b = a;
    EXPECT_TRUE(b.sharesBufferWith(a));
    EXPECT_EQ(b.data(), buffer);
    EXPECT_EQ(a.holderCount(), 2);

    b.forWrite()[1] = 0.25f; // shared: copied first
    EXPECT_FALSE(b.sharesBufferWith(a));
    EXPECT_EQ(a.data(), buffer);
    EXPECT_EQ(a[1], 0.5f);
    EXPECT_EQ(b[1], 0.25f);
    EXPECT_EQ(a.holderCount(), 1);

    const float* own = b.data();
    b.forWrite()[0] = 0.75f; // alone: written in place
    EXPECT_EQ(b.data(), own);
    EXPECT_EQ(b[0], 0.75f);
}

TEST(RegionWeights, ComparesValuesAndReadsAsASpan)
{
    const RegionWeights a = { 1.0f, 0.2f };
    const RegionWeights b = std::vector<float>{ 1.0f, 0.2f };
    EXPECT_FALSE(a.sharesBufferWith(b));
    EXPECT_EQ(a, b);
    EXPECT_NE(a, (RegionWeights{ 1.0f }));
    const std::span<const float> view = a;
    ASSERT_EQ(view.size(), 2u);
    EXPECT_EQ(view[1], 0.2f);
    EXPECT_EQ(a.toVector(), (std::vector<float>{ 1.0f, 0.2f }));

    RegionWeights none;
    EXPECT_TRUE(none.empty());
    EXPECT_EQ(none.holderCount(), 0);
    EXPECT_EQ(none, RegionWeights(std::vector<float>{}));
    none.assign(3, 0.5f);
    EXPECT_EQ(none, (RegionWeights{ 0.5f, 0.5f, 0.5f }));
}

TEST(RegionWeights, RegionCopiesShareWeightsAndKeepTheirOwnAfterAWrite)
{
    GrowthRegion scalp;
    scalp.name = "Scalp";
    scalp.weights = std::vector<float>(1000, 0.5f);
    const std::vector<GrowthRegion> snapshot{ scalp }; // what an undo command keeps
    EXPECT_TRUE(snapshot[0].weights.sharesBufferWith(scalp.weights));

    scalp.weights.forWrite()[10] = 1.0f;
    EXPECT_EQ(scalp.weights[10], 1.0f);
    EXPECT_EQ(snapshot[0].weights[10], 0.5f); // the snapshot is what it was
    EXPECT_NE(snapshot[0], scalp);
}

} // namespace
} // namespace wisp
