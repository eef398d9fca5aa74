// The hair dryer in the real window: it blows the hair in its cone away from the cursor, from the
// eye toward the surface, dries it, and shows its cone.
#include "StylingTestSupport.h"

using namespace wisp;
using namespace wisp::test;

namespace {

TEST_F(StylingTest, TheDryerBlowsTheHairInItsConeAwayFromTheCursorAndDriesIt)
{
    document()->editParameter(Param::DryingTime, 3600.0, false); // no drying but the dryer's
    settle();
    // Wet the right side first.
    look(90.0f, { box.center().x, box.center().y - 0.05f, box.center().z });
    pick(Qt::Key_W, StyleBrush::Wet);
    stroke({ rightSide(-0.02f, 0.08f) + glm::vec3(0.03f, 0, 0), rightSide(-0.02f, -0.08f) + glm::vec3(0.03f, 0, 0),
        rightSide(0.12f, -0.08f) + glm::vec3(0.03f, 0, 0), rightSide(0.12f, 0.08f) + glm::vec3(0.03f, 0, 0) });
    const StyleEdits wetStyle = *document()->style();
    ASSERT_GT(wetStyle.size(), 3u);
    runSteps(120); // wet hair is softer: let it settle

    // From the front, aim the dryer at the hair beside the right cheek: the air blows backward.
    const glm::vec3 aim{ box.center().x + 0.25f * box.size().x, box.center().y - 0.03f, box.center().z }; // the cheek
    look(0.0f, { box.center().x, aim.y, box.center().z }, 0.8f);
    pick(Qt::Key_D, StyleBrush::BlowDry);
    const FramePtr calm = frame();
    const int undoBefore = document()->undoStack()->count();
    Viewport* view = window->viewport();
    const QPoint at = screenOf(aim);
    const glm::vec3 axis = view->rayAt(at).direction;
    QTest::mousePress(view, Qt::LeftButton, Qt::NoModifier, at);
    // 90 steps at the requested substeps, stepped rather than played: played, the pacer sheds
    // substeps on a loaded machine and how far the hair blows would depend on the machine's speed.
    runSteps(90);
    const FramePtr blown = frame();
    QTest::mouseRelease(view, Qt::LeftButton, Qt::NoModifier, at);
    settle();

    // In a cone: keys whose outer half was in the air of the dryer, or of its mirror (X symmetry is
    // on, so a second dryer blows at the left side).
    HairDryer dryer;
    dryer.direction = axis;
    const auto hit = window->paintTool()->hitAt(at);
    ASSERT_TRUE(hit.has_value()) << "the dryer was not aimed at the head";
    const float hitDepth = glm::dot(hit->point - view->rayAt(at).origin, axis);
    dryer.nozzle = view->rayAt(at).origin + axis * (hitDepth - kDryerDistanceMetres);
    const TriangleMesh& head = document()->head();
    const float extent = std::max({ box.size().x, box.size().y, box.size().z });
    const SignedDistanceField field = SignedDistanceField::bake(head, extent / 96.0f, 0.1f * extent + 0.01f);
    HairDryer mirror = dryer;
    mirror.nozzle = mirroredPoint(dryer.nozzle, window->paintTool()->mirrorPlaneX());
    mirror.direction = mirroredDirection(dryer.direction);
    const Strands still = byIdentity(calm), moved = byIdentity(blown);
    const GroomShape& g = *calm->groomShape;
    double along[2] = { 0, 0 }, wetness[2] = { 0, 0 };
    int count[2] = { 0, 0 }, mirrored = 0;
    for (std::uint32_t w = 0; w < g.keyOfWisp.size(); ++w) {
        const std::uint32_t key = g.keyOfWisp[w];
        const std::uint64_t id = g.identities[key];
        const auto& strand = still.at(id);
        float air[2] = { 0.0f, 0.0f }, anyAir = 0.0f;
        for (int d = 0; d < 2; ++d) {
            const HairDryer& one = d == 0 ? dryer : mirror;
            for (std::size_t j = strand.size() / 2; j < strand.size(); ++j)
                air[d] += glm::length(dryerAirAt(one, strand[j], &field))
                    / static_cast<float>(strand.size() - strand.size() / 2);
            for (const glm::vec3& p : strand)
                anyAir = std::max(anyAir, glm::length(dryerAirAt(one, p, &field)));
        }
        const int which = air[1] > air[0] ? 1 : 0;
        if (air[which] < 1.0f && anyAir > 0.3f)
            continue; // a cone's edge (outside: no more than a breath of air anywhere on it)
        const bool inCone = air[which] >= 1.0f;
        mirrored += inCone && which == 1;
        along[inCone] += glm::dot(moved.at(id).back() - strand.back(), (which == 0 ? dryer : mirror).direction);
        ++count[inCone];
        if (inCone && wetStyle.count(id)) { // how wet it is now, of how wet the brush made it
            wetness[0] += wetStyle.at(id).wetness;
            wetness[1] += blown->wetness.empty() ? 0.0 : blown->wetness[key];
        }
    }
    EXPECT_GT(mirrored, 0) << "the mirrored dryer blew on nothing";
    ASSERT_GT(count[1], 2) << "no wet strand in the cone";
    ASSERT_GT(count[0], 2);
    std::printf("[ dryer    ] cone: %d keys, tips %.2f mm along the air; outside: %d keys, %.2f mm\n", count[1],
        1000.0 * along[1] / count[1], count[0], 1000.0 * along[0] / count[0]);
    EXPECT_GT(along[1] / count[1], 0.01) << "the hair in the cone did not move away from the cursor";
    EXPECT_LT(along[0] / count[0], 0.3 * along[1] / count[1]);
    ASSERT_GT(wetness[0], 0.0) << "no wet hair in the cones";
    EXPECT_LT(wetness[1], 0.6 * wetness[0]) << "the dryer did not dry the hair it blew on";

    // What it dried is one undo step, and undo brings the wetness back exactly.
    EXPECT_EQ(document()->undoStack()->count(), undoBefore + 1);
    EXPECT_NE(*document()->style(), wetStyle);
    undo();
    EXPECT_EQ(*document()->style(), wetStyle);
}

TEST_F(StylingTest, TheDryerBlowsFromTheEyeTowardTheSurfaceAndShowsItsCone)
{
    const glm::vec3 aim{ box.center().x + 0.25f * box.size().x, box.center().y - 0.03f, box.center().z };
    look(0.0f, { box.center().x, aim.y, box.center().z }, 0.8f);
    pick(Qt::Key_D, StyleBrush::BlowDry);
    Viewport* view = window->viewport();
    const QPoint at = screenOf(aim);
    QTest::mouseMove(view, at);
    ASSERT_TRUE(wisp::test::waitUntil([&] { return view->brushCursor().has_value(); }, 2000));
    const BrushCursor cursor = *view->brushCursor();
    EXPECT_TRUE(cursor.dryer) << "the dryer shows no cone";
    const ViewRay ray = view->rayAt(at);
    const auto hit = window->paintTool()->hitAt(at);
    ASSERT_TRUE(hit.has_value());
    const float hitDepth = glm::dot(hit->point - ray.origin, ray.direction);
    // The cone: from a nozzle between the eye and the surface to a rim around the aimed point.
    EXPECT_NEAR(glm::distance(cursor.dryerNozzle, hit->point), kDryerDistanceMetres, 1e-4f);
    EXPECT_LT(glm::distance(cursor.dryerNozzle, ray.origin), hitDepth);
    EXPECT_GT(cursor.radiusMetres, 0.02f);
    const std::vector<GuideVertex> cone
        = buildDryerCone(cursor.dryerNozzle, cursor.centre, cursor.dryerHalfAngleRadians, 0.002f, 1.0f);
    EXPECT_FALSE(cone.empty());

    QTest::mousePress(view, Qt::LeftButton, Qt::NoModifier, at);
    const std::vector<HairDryer> dryers = window->styleTool()->dryers();
    ASSERT_FALSE(dryers.empty()) << "no dryer blows while the button is held";
    const HairDryer& dryer = dryers.front();
    const glm::vec3 eyeToSurface = glm::normalize(hit->point - ray.origin);
    EXPECT_GT(glm::dot(dryer.direction, eyeToSurface), 0.9999f)
        << "the dryer does not blow from the eye at the surface";
    EXPECT_LT(glm::dot(dryer.direction, hit->normal), 0.0f) << "the dryer blows away from the surface";
    // The air reaches the aimed point, on the axis, at speed.
    EXPECT_GT(glm::length(dryerAirAt(dryer, hit->point)), 5.0f);
    if (const char* folder = std::getenv("WISP_TEST_SCREENSHOT_DIR")) {
        QTest::qWait(200);
        // The window, with the viewport's GL frame read back into its place (grab() leaves it blank).
        QImage shot = window->grab().toImage();
        QPainter painter(&shot);
        painter.drawImage(view->mapTo(window.get(), QPoint(0, 0)), view->grabFramebuffer());
        painter.end();
        shot.save(QString::fromLocal8Bit(folder) + QStringLiteral("/dryer-cone.png"));
    }
    QTest::mouseRelease(view, Qt::LeftButton, Qt::NoModifier, at);
    EXPECT_TRUE(window->styleTool()->dryers().empty());
    settle();
}

} // namespace
