// Imported strands land on their head: io/StrandPlacement.h, the one placement the editor's Import
// Hair and wisp-cli simulate --hair share. Checked against the head's surface (a BVH of the
// placed mesh), on CT2Hair's bangs and the head they were made on.
#include "io/StrandPlacement.h"
#include "IoTestSupport.h"
#include "io/HairFiles.h"
#include "io/HeadPlacement.h"
#include "io/MeshReader.h"
#include "sim/geometry/MeshBvh.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <vector>

using namespace wisp;
using namespace wisp::io;
using wisp::test::assetPath;

namespace {

HairCurves readBangs()
{
    Result<HairReadResult> read = readHair(assetPath("hair/ct2hair_bangs100.data").string());
    EXPECT_TRUE(read.ok()) << read.error().toString();
    return read ? std::move(read).value().strands : HairCurves{};
}

std::vector<float> strandLengths(const HairCurves& strands)
{
    std::vector<float> lengths;
    for (std::size_t s = 0; s < strands.strandCount(); ++s) {
        float length = 0.0f;
        for (std::uint32_t i = strands.offsets[s] + 1; i < strands.offsets[s + 1]; ++i)
            length += glm::distance(strands.positions[i - 1], strands.positions[i]);
        lengths.push_back(length);
    }
    return lengths;
}

} // namespace

TEST(StrandPlacement, BangsRootsLieOnTheirHeadAfterPlacement)
{
    const auto headPath = assetPath("hair/ct2hair_bangs_head.ply");
    REQUIRE_ASSET(headPath);
    Result<MeshReadResult> read = readMesh(headPath.string());
    ASSERT_TRUE(read.ok()) << read.error().toString();
    TriangleMesh head = std::move(read).value().mesh;
    const HeadPlacement placement = placeHead(head);
    ASSERT_EQ(placement.up, Axis::PosX) << placement.orientation; // turned: the strands must turn with it

    HairCurves strands = readBangs();
    const StrandPlacement placed = placeStrands(strands, &placement);
    EXPECT_TRUE(placed.followedHead);
    const MeshBvh bvh(head);
    float worst = 0.0f, sum = 0.0f;
    for (std::size_t s = 0; s < strands.strandCount(); ++s) {
        const float d = bvh.closestPoint(strands.positions[strands.offsets[s]]).distance;
        worst = std::max(worst, d);
        sum += d;
    }
    std::cout << "[          ] bangs roots to the placed head: mean " << sum / float(strands.strandCount()) * 1000.0f
              << " mm, worst " << worst * 1000.0f << " mm\n";
    EXPECT_LT(worst, 0.006f) << "roots within a few millimetres of the scalp";
    // And the hair hangs down: tips below roots on the whole.
    float drop = 0.0f;
    for (std::size_t s = 0; s < strands.strandCount(); ++s)
        drop += strands.positions[strands.offsets[s]].y - strands.positions[strands.offsets[s + 1] - 1].y;
    EXPECT_GT(drop / float(strands.strandCount()), 0.02f);
}

// Without their head the unit is found from the span of the roots, as a head's is from its skull.
TEST(StrandPlacement, TheUnitOfAGroomIsFoundFromItsRoots)
{
    REQUIRE_ASSET(assetPath("hair/ct2hair_bangs100.data"));
    const HairCurves millimetres = readBangs();
    const std::vector<float> lengthsMm = strandLengths(millimetres);
    for (const auto& [unit, perMillimetre] : { std::pair{ LengthUnit::Millimetres, 1.0f },
             std::pair{ LengthUnit::Centimetres, 0.1f }, std::pair{ LengthUnit::Metres, 0.001f } }) {
        HairCurves strands = millimetres;
        for (glm::vec3& p : strands.positions)
            p *= perMillimetre;
        const StrandPlacement placed = placeStrands(strands, nullptr);
        EXPECT_EQ(placed.unit, unit) << placed.description << placed.note;
        EXPECT_TRUE(placed.note.empty()) << placed.note;
        const std::vector<float> lengths = strandLengths(strands);
        for (std::size_t s = 0; s < lengths.size(); ++s)
            ASSERT_NEAR(lengths[s], lengthsMm[s] * 0.001f, 1e-5f) << unitName(unit) << " strand " << s;
        EXPECT_LT(*std::max_element(lengths.begin(), lengths.end()), 0.25f) << unitName(unit);
    }

    // A chosen factor wins; a groom that fits no unit is left as it is, with a warning.
    HairCurves chosen = millimetres;
    EXPECT_EQ(placeStrands(chosen, nullptr, 0.002f).scale, 0.002f);
    EXPECT_NEAR(chosen.positions[0].x, millimetres.positions[0].x * 0.002f, 1e-6f);
    HairCurves tiny = millimetres;
    for (glm::vec3& p : tiny.positions)
        p *= 1e-5f;
    const StrandPlacement none = placeStrands(tiny, nullptr);
    EXPECT_EQ(none.unit, LengthUnit::Auto);
    EXPECT_NE(none.note.find("no scalp"), std::string::npos) << none.note;
    EXPECT_EQ(tiny.positions[3], millimetres.positions[3] * 1e-5f);
}
