// The salon brushes as operations (sim/style/), headless: each brush's stroke on the default head's
// groom, measured on the edits it leaves and the live effects it asks for.
#include "SimFixtures.h"

#include "sim/style/BlowDryOperation.h"
#include "sim/style/CombOperation.h"
#include "sim/style/CutOperation.h"
#include "sim/style/LengthOperation.h"
#include "sim/style/StrandPicking.h"
#include "sim/style/StyleOperation.h"
#include "sim/style/WispDabOperation.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>

using namespace wisp;
using wisp::test::defaultHead;

namespace {

const HeadModelPtr& headModel()
{
    static const HeadModelPtr head = std::make_shared<const HeadModel>(defaultHead().mesh);
    return head;
}

// The default groom at rest, as a frame the brushes read (groomed once for every test here).
FramePtr restFrame()
{
    static const FramePtr frame = [] {
        auto sim = wisp::test::makeSimulation(wisp::test::testParameters(), 1);
        auto f = std::make_shared<Frame>();
        sim->buildFrame(f->strands);
        f->groomShape = groomShapeOf(*sim);
        return f;
    }();
    return frame;
}

// The brush context on that frame, and a key hair with members hanging at the back.
struct Salon {
    BrushContext context;
    std::uint32_t key = 0; // a key hair at the back of the head
    glm::vec3 middle_ws{ 0.0f }; // its point halfway along

    Salon()
    {
        const FramePtr frame = restFrame();
        context.frame = frame;
        context.head = headModel();
        context.brush.radiusMetres = 0.01f;
        context.brush.strength = 1.0f;
        context.brush.falloff = 0.0f;
        context.brush.mirrorX = false;
        float backmost = 1e9f;
        for (std::uint32_t k : frame->groomShape->keyOfWisp) {
            const auto points = frame->strands.strand(k);
            const glm::vec3 mid = points[points.size() / 2];
            const auto members = std::count(
                frame->groomShape->wispOf.begin(), frame->groomShape->wispOf.end(), frame->groomShape->wispOf[k]);
            if (mid.z < backmost && std::abs(mid.x) < 0.03f && members > 1) {
                backmost = mid.z;
                key = k;
                middle_ws = mid;
            }
        }
    }
    const GroomShape& shape() const { return *context.frame->groomShape; }
    std::uint64_t id(std::uint32_t strand) const { return shape().identities[strand]; }
    // The view from behind the head, 0.4 m away, through `target`.
    static BrushSample lookAt(const glm::vec3& target_ws, bool inverted = false)
    {
        BrushSample s;
        s.eye_ws = glm::vec3(target_ws.x, target_ws.y, target_ws.z - 0.4f);
        s.direction_ws = glm::normalize(target_ws - s.eye_ws);
        s.aimDepthMetres = 0.4f;
        s.inverted = inverted;
        return s;
    }
};

} // namespace

TEST(StyleOperation, FactoryMakesOneOperationPerBrush)
{
    EXPECT_NE(dynamic_cast<CombOperation*>(makeStyleOperation(StyleBrush::Comb).get()), nullptr);
    EXPECT_NE(dynamic_cast<CutOperation*>(makeStyleOperation(StyleBrush::Cut).get()), nullptr);
    EXPECT_NE(dynamic_cast<LengthOperation*>(makeStyleOperation(StyleBrush::Length).get()), nullptr);
    EXPECT_NE(dynamic_cast<CurlOperation*>(makeStyleOperation(StyleBrush::Curl).get()), nullptr);
    EXPECT_NE(dynamic_cast<WetOperation*>(makeStyleOperation(StyleBrush::Wet).get()), nullptr);
    EXPECT_NE(dynamic_cast<HairsprayOperation*>(makeStyleOperation(StyleBrush::Hairspray).get()), nullptr);
    EXPECT_NE(dynamic_cast<BlowDryOperation*>(makeStyleOperation(StyleBrush::BlowDry).get()), nullptr);
}

TEST(StyleOperation, NothingHappensBeforeTheHairIsGroomed)
{
    Salon salon;
    BrushContext empty = salon.context;
    empty.frame = std::make_shared<Frame>(); // no groom shape: a frame from before the first groom
    StyleEdits edits;
    for (StyleBrush brush : { StyleBrush::Comb, StyleBrush::Cut, StyleBrush::Length, StyleBrush::Curl, StyleBrush::Wet,
             StyleBrush::Hairspray }) {
        auto op = makeStyleOperation(brush);
        EXPECT_FALSE(op->begin(empty, Salon::lookAt(salon.middle_ws), edits).editsChanged);
        EXPECT_FALSE(op->step(empty, Salon::lookAt(salon.middle_ws + glm::vec3(0.02f, 0, 0)), edits).editsChanged);
    }
    EXPECT_TRUE(edits.empty());
}

TEST(CombOperation, DragsTheCaughtStrandAlongTheStrokeAndKeepsItsRootAndLength)
{
    Salon salon;
    CombOperation comb;
    StyleEdits edits;
    const StyleEffects caught = comb.begin(salon.context, Salon::lookAt(salon.middle_ws), edits);
    ASSERT_TRUE(caught.held.has_value());
    const std::size_t caughtCount = comb.caughtStrands();
    ASSERT_GT(caughtCount, 0u);
    const auto before = salon.context.frame->strands.strand(salon.key);
    const std::vector<glm::vec3> before_ws(before.begin(), before.end());
    // 30 mm to the side (+x), in three moves.
    for (int i = 1; i <= 3; ++i)
        comb.step(salon.context, Salon::lookAt(salon.middle_ws + glm::vec3(0.01f * i, 0.0f, 0.0f)), edits);
    const StyleEffects ended = comb.end(salon.context, edits);
    EXPECT_TRUE(ended.editsChanged);
    ASSERT_TRUE(ended.held.has_value());
    EXPECT_TRUE(ended.held->empty()) << "the comb lets go as the stroke ends";
    ASSERT_TRUE(edits.count(salon.id(salon.key)));
    const std::vector<glm::vec3>& after_ws = edits.at(salon.id(salon.key)).shape;
    ASSERT_EQ(after_ws.size(), before_ws.size());
    EXPECT_EQ(after_ws.front(), before_ws.front()) << "the root stays";
    EXPECT_NEAR(strandLength(after_ws), strandLength(before_ws), 1e-4f) << "the comb does not stretch the strand";
    // The tip is pulled by the whole 30 mm (share of arc length 1, weight 1 at strength 1 and no
    // falloff), less what keeping each segment's length takes back: at least half of it survives.
    const glm::vec3 tipMoved = after_ws.back() - before_ws.back();
    EXPECT_GT(tipMoved.x, 0.015f);
    EXPECT_LT(tipMoved.x, 0.0301f);
    // The point under the comb (halfway) is pulled by about half the stroke.
    const glm::vec3 midMoved = after_ws[after_ws.size() / 2] - before_ws[before_ws.size() / 2];
    EXPECT_GT(midMoved.x, 0.008f);
    EXPECT_LT(midMoved.x, 0.0201f);
    // Only the caught (key) strands are edited; the wisps they lead move with them, and the artist
    // is told about every drawn strand that moved.
    EXPECT_EQ(edits.size(), caughtCount);
    EXPECT_GT(comb.changedStrands(static_cast<int>(edits.size())), static_cast<int>(edits.size()));
    EXPECT_EQ(comb.changedStrands(0), 0);
}

TEST(CombOperation, MirrorCatchesTheStrandOnTheOtherSide)
{
    Salon salon;
    // A key hair well off the mirror plane, and its mirror image's nearest key hair.
    const GroomShape& shape = salon.shape();
    std::uint32_t side = 0;
    for (std::uint32_t k : shape.keyOfWisp) {
        const auto points = salon.context.frame->strands.strand(k);
        if (points[points.size() / 2].x > 0.05f && points[points.size() / 2].z < -0.05f) {
            side = k;
            break;
        }
    }
    const auto points = salon.context.frame->strands.strand(side);
    const glm::vec3 target = points[points.size() / 2];
    salon.context.brush.radiusMetres = 0.005f;
    StyleEdits edits;
    CombOperation alone;
    alone.begin(salon.context, Salon::lookAt(target), edits);
    salon.context.brush.mirrorX = true;
    CombOperation mirrored;
    mirrored.begin(salon.context, Salon::lookAt(target), edits);
    ASSERT_GT(alone.caughtStrands(), 0u);
    EXPECT_GT(mirrored.caughtStrands(), alone.caughtStrands()) << "the mirrored ring catches strands too";
}

TEST(CutOperation, CutsTheCrossedStrandWhereTheBladeCrossesItAndItsWispWithIt)
{
    Salon salon;
    const auto points = salon.context.frame->strands.strand(salon.key);
    const glm::vec3 middle = salon.middle_ws;
    CutOperation cut;
    StyleEdits edits;
    const glm::vec3 eye = middle + glm::vec3(0.0f, 0.0f, -0.4f);
    auto through = [&](const glm::vec3& p) {
        BrushSample s;
        s.eye_ws = eye;
        s.direction_ws = glm::normalize(p - eye);
        return s;
    };
    // A horizontal blade, 6 cm wide, across the strand's middle.
    cut.begin(salon.context, through(middle - glm::vec3(0.03f, 0.0f, 0.0f)), edits);
    const StyleEffects effects = cut.step(salon.context, through(middle + glm::vec3(0.03f, 0.0f, 0.0f)), edits);
    EXPECT_TRUE(effects.editsChanged);
    ASSERT_TRUE(edits.count(salon.id(salon.key)));
    // The crossing is the strand's point halfway along (by point count): the cut keeps the share of
    // the groomed length up to there.
    const float groomed = salon.shape().lengths[salon.key];
    const float drawnToMiddle = strandLength(points.first(points.size() / 2 + 1));
    const float expected = drawnToMiddle / strandLength(points) * groomed;
    EXPECT_NEAR(edits.at(salon.id(salon.key)).lengthMetres, expected, 0.01f * groomed);
    EXPECT_LT(edits.at(salon.id(salon.key)).lengthMetres, 0.7f * groomed);
    // Every member of its wisp is cut about where its key is (a member the blade crossed, at its own
    // crossing; one it missed, to its key's length), well short of its groomed length.
    const std::uint32_t wisp = salon.shape().wispOf[salon.key];
    int members = 0;
    for (std::uint32_t i = 0; i < salon.shape().wispOf.size(); ++i)
        if (salon.shape().wispOf[i] == wisp && i != salon.key) {
            ++members;
            ASSERT_TRUE(edits.count(salon.id(i))) << "member " << i;
            const float keyCut = edits.at(salon.id(salon.key)).lengthMetres;
            EXPECT_NEAR(edits.at(salon.id(i)).lengthMetres, keyCut, 0.1f * keyCut) << "member " << i;
            EXPECT_LT(edits.at(salon.id(i)).lengthMetres, 0.7f * salon.shape().lengths[i]) << "member " << i;
        }
    EXPECT_GT(members, 0);
}

TEST(CutOperation, DoesNotCutThroughTheHead)
{
    Salon salon;
    CutOperation cut;
    StyleEdits edits;
    // From in front of the face, a blade at the height of the back hair's middle: the head hides it.
    const glm::vec3 eye(0.0f, salon.middle_ws.y, 0.6f);
    BrushSample a, b;
    a.eye_ws = b.eye_ws = eye;
    a.direction_ws = glm::normalize(salon.middle_ws + glm::vec3(-0.01f, 0.0f, 0.0f) - eye);
    b.direction_ws = glm::normalize(salon.middle_ws + glm::vec3(0.01f, 0.0f, 0.0f) - eye);
    cut.begin(salon.context, a, edits);
    cut.step(salon.context, b, edits);
    EXPECT_FALSE(edits.count(salon.id(salon.key)));
}

TEST(LengthOperation, GrowsByTheStepShareAndShrinksWhenInverted)
{
    Salon salon;
    const float groomed = salon.shape().lengths[salon.key];
    StyleEdits edits;
    LengthOperation grow;
    grow.begin(salon.context, Salon::lookAt(salon.middle_ws), edits);
    ASSERT_TRUE(edits.count(salon.id(salon.key)));
    // Full strength, no falloff: one dab adds 6 % of the length.
    EXPECT_NEAR(edits.at(salon.id(salon.key)).lengthMetres, groomed * (1.0f + LengthOperation::kStepShare), 1e-5f);
    grow.step(salon.context, Salon::lookAt(salon.middle_ws), edits);
    EXPECT_NEAR(edits.at(salon.id(salon.key)).lengthMetres,
        groomed * (1.0f + LengthOperation::kStepShare) * (1.0f + LengthOperation::kStepShare), 1e-5f);
    StyleEdits shrunk;
    LengthOperation shrink;
    salon.context.brush.strength = 0.5f;
    shrink.begin(salon.context, Salon::lookAt(salon.middle_ws, true), shrunk);
    EXPECT_NEAR(
        shrunk.at(salon.id(salon.key)).lengthMetres, groomed * (1.0f - 0.5f * LengthOperation::kStepShare), 1e-5f);
    EXPECT_TRUE(grow.dabs());
}

TEST(CurlOperation, PermsEachTouchedWispOncePerStrokeAndInvertedTakesItOut)
{
    Salon salon;
    salon.context.curlRadiusMetres = 0.02f;
    salon.context.curlTurnsPerMetre = 25.0f;
    StyleEdits edits;
    edits[salon.id(salon.key)].shape = { glm::vec3(0.0f), glm::vec3(0.0f, -0.1f, 0.0f) }; // combed before
    CurlOperation perm;
    EXPECT_TRUE(perm.begin(salon.context, Salon::lookAt(salon.middle_ws), edits).editsChanged);
    const StrandStyle& e = edits.at(salon.id(salon.key));
    EXPECT_EQ(e.curlRadiusMetres, 0.02f);
    EXPECT_EQ(e.curlTurnsPerMetre, 25.0f);
    EXPECT_TRUE(e.shape.empty()) << "a perm re-forms the hair: the combed shape gives way";
    EXPECT_FALSE(perm.step(salon.context, Salon::lookAt(salon.middle_ws), edits).editsChanged)
        << "the same wisps again in one stroke: nothing new";
    // Only key hairs carry the perm (members follow their key).
    for (const auto& [id, style] : edits) {
        const auto at = std::find(salon.shape().identities.begin(), salon.shape().identities.end(), id);
        const auto strand = static_cast<std::uint32_t>(at - salon.shape().identities.begin());
        EXPECT_EQ(salon.shape().keyOfWisp[salon.shape().wispOf[strand]], strand);
    }
    CurlOperation out;
    out.begin(salon.context, Salon::lookAt(salon.middle_ws, true), edits);
    EXPECT_EQ(edits.at(salon.id(salon.key)).curlRadiusMetres, -1.0f);
    EXPECT_EQ(edits.at(salon.id(salon.key)).curlTurnsPerMetre, -1.0f);
}

TEST(WetOperation, WetsTheWispsAtTheStrengthAndAsksTheSimulationToWetThemNow)
{
    Salon salon;
    salon.context.brush.strength = 0.7f;
    StyleEdits edits;
    WetOperation wet;
    const StyleEffects effects = wet.begin(salon.context, Salon::lookAt(salon.middle_ws), edits);
    EXPECT_FLOAT_EQ(edits.at(salon.id(salon.key)).wetness, 0.7f);
    EXPECT_FLOAT_EQ(effects.wetness, 0.7f);
    EXPECT_NE(
        std::find(effects.wettedKeys.begin(), effects.wettedKeys.end(), salon.id(salon.key)), effects.wettedKeys.end());
    EXPECT_EQ(effects.wettedKeys.size(), edits.size());
    WetOperation towel;
    const StyleEffects dried = towel.begin(salon.context, Salon::lookAt(salon.middle_ws, true), edits);
    EXPECT_EQ(edits.at(salon.id(salon.key)).wetness, 0.0f);
    EXPECT_TRUE(dried.wettedKeys.empty());
}

TEST(HairsprayOperation, StiffensByTheStrengthAndHoldsTheShapeItHasNow)
{
    Salon salon;
    salon.context.brush.strength = 0.5f;
    StyleEdits edits;
    HairsprayOperation spray;
    spray.begin(salon.context, Salon::lookAt(salon.middle_ws), edits);
    const StrandStyle& e = edits.at(salon.id(salon.key));
    // No falloff: weight 1 at the strand, 1 + 9 * 0.5 * 1.
    EXPECT_FLOAT_EQ(e.stiffnessScale, 5.5f);
    const auto now = salon.context.frame->strands.strand(salon.key);
    EXPECT_EQ(e.shape, std::vector<glm::vec3>(now.begin(), now.end()));
    HairsprayOperation again; // a second stroke stiffens further, up to the limit
    again.begin(salon.context, Salon::lookAt(salon.middle_ws), edits);
    EXPECT_FLOAT_EQ(edits.at(salon.id(salon.key)).stiffnessScale, std::min(5.5f * 5.5f, kStyleMaxStiffnessScale));
    HairsprayOperation wash;
    wash.begin(salon.context, Salon::lookAt(salon.middle_ws, true), edits);
    EXPECT_EQ(edits.at(salon.id(salon.key)).stiffnessScale, 1.0f);
    EXPECT_TRUE(edits.at(salon.id(salon.key)).shape.empty());
}

TEST(BlowDryOperation, AimsAtTheHeadAndKeepsWhatItDried)
{
    Salon salon;
    salon.context.brush.mirrorX = true;
    StyleEdits edits;
    edits[salon.id(salon.key)].wetness = 0.8f;
    BlowDryOperation dryer;
    // From the right of the head, level with its centre: the air hits the head's side.
    BrushSample sample;
    sample.eye_ws = glm::vec3(0.6f, 0.1f, 0.0f);
    sample.direction_ws = glm::vec3(-1.0f, 0.0f, 0.0f);
    const StyleEffects blowing = dryer.begin(salon.context, sample, edits);
    ASSERT_TRUE(blowing.dryers.has_value());
    ASSERT_EQ(blowing.dryers->size(), 2u) << "X mirror: a second dryer";
    const auto hit = headModel()->hitAlong(sample.eye_ws, sample.direction_ws);
    ASSERT_TRUE(hit.has_value());
    const HairDryer& right = blowing.dryers->front();
    EXPECT_NEAR(glm::distance(right.nozzle, hit->point), kDryerDistanceMetres, 1e-5f);
    EXPECT_NEAR(right.direction.x, -1.0f, 1e-5f);
    const HairDryer& left = blowing.dryers->back();
    EXPECT_NEAR(left.nozzle.x, 2.0f * headModel()->mirrorPlaneX() - right.nozzle.x, 1e-5f);
    EXPECT_NEAR(left.direction.x, 1.0f, 1e-5f);
    // The simulation dried the wisp to 0.3: the stroke keeps that.
    auto dried = std::make_shared<Frame>(*salon.context.frame);
    dried->wetness.assign(dried->strands.strandCount(), 0.0f);
    dried->wetness[salon.key] = 0.3f;
    salon.context.frame = dried;
    const StyleEffects ended = dryer.end(salon.context, edits);
    EXPECT_TRUE(ended.editsChanged);
    ASSERT_TRUE(ended.dryers.has_value());
    EXPECT_TRUE(ended.dryers->empty()) << "the dryers are put down";
    EXPECT_FLOAT_EQ(edits.at(salon.id(salon.key)).wetness, 0.3f);
}

// Issue 17: the head turned and moved (the frame's headToWorld). A stroke seen from an eye moved
// with it catches the same strands (the head stops the rays in head space, the mirror plane is the
// head's) and leaves the same edits, in head space, as the stroke on the head at rest.
TEST(CombOperation, OnAMovedHeadCatchesAndEditsAsOnTheHeadAtRest)
{
    Salon rest;
    rest.context.brush.mirrorX = true;
    const glm::mat4 headToWorld = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(0.2f, 0.05f, 0.1f)),
        glm::radians(40.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    auto movedFrame = std::make_shared<Frame>(*rest.context.frame);
    for (glm::vec3& p : movedFrame->strands.positions)
        p = glm::vec3(headToWorld * glm::vec4(p, 1.0f));
    movedFrame->headToWorld = headToWorld;
    BrushContext moved = rest.context;
    moved.frame = movedFrame;
    const auto place = [&](BrushSample s) {
        s.eye_ws = glm::vec3(headToWorld * glm::vec4(s.eye_ws, 1.0f));
        s.direction_ws = glm::mat3(headToWorld) * s.direction_ws;
        return s;
    };

    CombOperation atRest, turned;
    StyleEdits restEdits, turnedEdits;
    atRest.begin(rest.context, Salon::lookAt(rest.middle_ws), restEdits);
    turned.begin(moved, place(Salon::lookAt(rest.middle_ws)), turnedEdits);
    ASSERT_GT(atRest.caughtStrands(), 0u);
    EXPECT_EQ(turned.caughtStrands(), atRest.caughtStrands());
    for (int i = 1; i <= 3; ++i) {
        const BrushSample s = Salon::lookAt(rest.middle_ws + glm::vec3(0.01f * i, 0.0f, 0.0f));
        atRest.step(rest.context, s, restEdits);
        turned.step(moved, place(s), turnedEdits);
    }
    atRest.end(rest.context, restEdits);
    turned.end(moved, turnedEdits);
    ASSERT_EQ(turnedEdits.size(), restEdits.size());
    float worst = 0.0f;
    for (const auto& [id, style] : restEdits) {
        ASSERT_TRUE(turnedEdits.count(id)) << "strand " << id;
        const std::vector<glm::vec3>& a = style.shape;
        const std::vector<glm::vec3>& b = turnedEdits.at(id).shape;
        ASSERT_EQ(a.size(), b.size());
        for (std::size_t j = 0; j < a.size(); ++j)
            worst = std::max(worst, glm::distance(a[j], b[j]));
    }
    EXPECT_LT(worst, 1e-5f) << "the combed shapes are head space, as at rest";

    // The dryer aims where the turned head is: at the same head point as at rest, placed.
    const HairDryer atRestDryer = dryersFor(rest.context, Salon::lookAt(rest.middle_ws)).front();
    const HairDryer turnedDryer = dryersFor(moved, place(Salon::lookAt(rest.middle_ws))).front();
    EXPECT_LT(glm::distance(turnedDryer.nozzle, glm::vec3(headToWorld * glm::vec4(atRestDryer.nozzle, 1.0f))), 1e-5f);
}

// One head-to-world for brushes and the editor's tools (Frame.h): the frame's transform, identity
// before the first frame, and its inverse the way back. The brushes' picking goes through it: a
// ray on the moved head meets it at the head-space hit carried to the world.
TEST(BrushContext, HeadToWorldIsTheFramesOneTransformForBrushesAndTools)
{
    EXPECT_EQ(headToWorldOf(FramePtr{}), glm::mat4(1.0f));
    EXPECT_EQ(worldToHeadOf(FramePtr{}), glm::mat4(1.0f));

    Salon rest;
    const glm::mat4 headToWorld = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(-0.1f, 0.2f, 0.03f)),
        glm::radians(-25.0f), glm::vec3(1.0f, 0.0f, 0.0f));
    auto movedFrame = std::make_shared<Frame>(*rest.context.frame);
    movedFrame->headToWorld = headToWorld;
    BrushContext moved = rest.context;
    moved.frame = movedFrame;
    EXPECT_EQ(headToWorldOf(moved.frame), headToWorld);
    const glm::mat4 roundTrip = worldToHeadOf(moved.frame) * headToWorld;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            EXPECT_NEAR(roundTrip[c][r], c == r ? 1.0f : 0.0f, 1e-6f) << c << "," << r;

    const BrushSample look = Salon::lookAt(rest.middle_ws);
    const auto atRest = headHitAlong(rest.context, look.eye_ws, look.direction_ws);
    const auto turned = headHitAlong(
        moved, glm::vec3(headToWorld * glm::vec4(look.eye_ws, 1.0f)), glm::mat3(headToWorld) * look.direction_ws);
    ASSERT_TRUE(atRest.has_value());
    ASSERT_TRUE(turned.has_value());
    EXPECT_LT(glm::distance(turned->point, glm::vec3(headToWorld * glm::vec4(atRest->point, 1.0f))), 1e-5f);
}
