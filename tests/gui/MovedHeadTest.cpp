// The head moved by its transform (issue 17) is drawn, shadowed and lit where it is: a head and
// its hair moved together by a translation, seen from a camera moved by the same translation, look
// exactly as they do at rest. The key light is fixed in the world and the shadow map is an
// orthographic view down it, so a translation changes nothing in the image: the head casting its
// shadow and taking the hair's (HairShadowMap) must use the frame's headToWorld as the main pass
// does, and so must the hair's shading about the cranium. And the growth brush paints a turned
// head where the cursor is on it, and nothing where the cursor misses it.
#include "GuiTestSupport.h"
#include "app/editor/Document.h"
#include "app/editor/MainWindow.h"
#include "app/editor/PaintTool.h"
#include "app/editor/SimulationHost.h"
#include "sim/geometry/Body.h"
#include "sim/geometry/DefaultHead.h"
#include "sim/geometry/MeshBvh.h"
#include "sim/motion/HeadMotion.h"
#include "sim/params/Parameters.h"
#include "sim/solver/Frame.h"
#include "sim/solver/HairSimulation.h"
#include "widgets/OrbitCamera.h"
#include "widgets/Viewport.h"

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include <QAction>
#include <QImage>
#include <QSignalSpy>
#include <QTest>
#include <QUndoStack>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>

using namespace wisp;

namespace {

// A light groom over the default head, draped at rest (head space = world at rest).
FramePtr restFrame(const DefaultHead& head)
{
    ParameterValues values;
    values.set(Param::Density, 2.0);
    HairSimulation simulation(1);
    EXPECT_EQ(simulation.setup(head.mesh, head.growthWeights, values), "");
    simulation.drapeAtRest(60);
    auto out = std::make_shared<Frame>();
    simulation.buildFrame(out->strands);
    out->simulatedStrands = out->strands.strandCount();
    out->simulatedParticles = out->strands.pointCount();
    return out;
}

// Pixels whose colour differs by more than `tolerance` levels in a channel, below the HUD line.
int differingPixels(const QImage& a, const QImage& b, int tolerance)
{
    int count = 0;
    for (int y = 40; y < std::min(a.height(), b.height()); ++y)
        for (int x = 0; x < std::min(a.width(), b.width()); ++x) {
            const QColor p = a.pixelColor(x, y);
            const QColor q = b.pixelColor(x, y);
            count += std::max({ std::abs(p.red() - q.red()), std::abs(p.green() - q.green()),
                         std::abs(p.blue() - q.blue()) })
                    > tolerance
                ? 1
                : 0;
        }
    return count;
}

} // namespace

TEST(MovedHeadTest, AHeadMovedWithItsHairLooksAsAtRestFromACameraMovedAlike)
{
    const DefaultHead head = makeDefaultHead();
    Viewport viewport;
    viewport.resize(480, 480);
    viewport.setHead(head.mesh);
    viewport.setBody(defaultBody(head.mesh));
    viewport.setShowGrid(false); // the grid stays on the floor: it is not moved
    viewport.setLevelOfDetail(false);
    viewport.setHairColours(QColor(60, 40, 25), QColor(130, 90, 50));
    viewport.show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(&viewport));
    ASSERT_TRUE(viewport.glStatus().isEmpty()) << viewport.glStatus().toStdString();
    ASSERT_TRUE(viewport.shadowsEnabled());
    const Aabb bounds = viewport.headBounds();
    const glm::vec3 top{ bounds.center().x, bounds.max.y, bounds.center().z };
    viewport.camera().setPivot(top - glm::vec3(0.0f, 0.08f, 0.0f)); // the crown, where the hair shades the skin

    const FramePtr rest = restFrame(head);
    ASSERT_GT(rest->strands.strandCount(), 500u);
    viewport.setFrame(rest);
    const QImage atRest = viewport.grabFramebuffer().convertToFormat(QImage::Format_RGB32);

    // 30 cm to the side, 10 cm up, 20 cm back: the head, the body and the hair together.
    const glm::vec3 moveMetres(0.3f, 0.1f, -0.2f);
    auto moved = std::make_shared<Frame>(*rest);
    for (glm::vec3& p : moved->strands.positions)
        p += moveMetres;
    moved->headToWorld = glm::translate(glm::mat4(1.0f), moveMetres);
    moved->headTranslationMetres = moveMetres;
    viewport.setFrame(moved);
    viewport.camera().setPivot(viewport.camera().pivot() + moveMetres);
    const QImage movedImage = viewport.grabFramebuffer().convertToFormat(QImage::Format_RGB32);

    // Without hair: how much of the image the hair's shadows and shading account for.
    viewport.setFrame(nullptr);
    const QImage bare = viewport.grabFramebuffer().convertToFormat(QImage::Format_RGB32);
    const int hairAndShadow = differingPixels(bare, movedImage, 8);
    const int differing = differingPixels(atRest, movedImage, 8);
    std::printf("[ moved    ] %d pixels show the hair or its shadow; %d differ between the head at rest and moved\n",
        hairAndShadow, differing);
    ASSERT_GT(hairAndShadow, 480 * 480 / 10);
    // Float rounding of the moved points and of the shadow map's placement: a few edge pixels.
    EXPECT_LE(differing, 480 * 480 / 1000);
}

namespace {

// Where a world ray meets the head placed by `headToWorld`, head space (the test's own geometry:
// the BVH and the inverse transform).
std::optional<glm::vec3> headHit(const MeshBvh& bvh, const ViewRay& ray_ws, const glm::mat4& headToWorld)
{
    const glm::mat4 toHead = glm::affineInverse(headToWorld);
    const auto hit
        = bvh.raycast(glm::vec3(toHead * glm::vec4(ray_ws.origin, 1.0f)), glm::mat3(toHead) * ray_ws.direction, 100.0f);
    return hit ? std::optional<glm::vec3>(hit->point) : std::nullopt;
}

} // namespace

TEST(MovedHeadTest, PaintingATurnedHeadLandsUnderTheCursorAndAMissPaintsNothing)
{
    auto window = wisp::test::openEditor();
    Document* doc = window->document();
    SimulationHost* host = window->simulation();
    doc->editRegionParameter(0, Param::Density, 2.0, false); // a light groom: quick regrooms
    doc->undoStack()->clear();
    ASSERT_TRUE(wisp::test::waitForFirstFrame(*host));
    if (window->playAction()->isChecked())
        window->playAction()->trigger();
    ASSERT_TRUE(wisp::test::waitUntil([&] { return !host->isPlaying(); }));

    // The head turned a quarter to its left (its face toward +X) and raised 2 cm: one key.
    HeadPose pose;
    pose.rotation = glm::angleAxis(glm::radians(90.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    pose.translationMetres = glm::vec3(0.0f, 0.02f, 0.0f);
    HeadMotion turned;
    turned.setKey(0.0, pose);
    ASSERT_EQ(doc->setHeadMotion(turned, QStringLiteral("Turn")), QString());
    doc->undoStack()->clear();
    const glm::mat4 expected = headToWorld(pose, pivotOf(doc->head()));
    Viewport* view = window->viewport();
    const auto placed = [&] {
        const FramePtr f = view->frame();
        if (!f)
            return false;
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r)
                if (std::abs(f->headToWorld[c][r] - expected[c][r]) > 1e-5f)
                    return false;
        return true;
    };
    // Steps until the viewport draws the head turned (it eases there over 0.15 s of steps, and a
    // regroom after painting starts it again from its pose at 0 s).
    const auto stepUntilPlaced = [&] {
        QSignalSpy ready(host, &SimulationHost::sceneReady);
        while (ready.wait(600 * WISP_SLOW_BUILD_FACTOR)) { } // no regroom pending
        for (int i = 0; i < 120 && !placed(); ++i) {
            const std::uint64_t before = host->publishedFrames();
            host->stepOnce();
            if (!wisp::test::waitForFramesSince(*host, before, 1))
                return false;
            wisp::test::waitUntil([&] { return view->frame() == host->latestFrame(); });
        }
        return placed();
    };
    ASSERT_TRUE(stepUntilPlaced()) << "the viewport does not draw the head turned";

    // Seen from +X: the turned head's face.
    view->camera().setOrientation(glm::radians(90.0f), 0.0f);
    view->update();
    QTest::keyClick(view, Qt::Key_B);
    ASSERT_TRUE(window->paintTool()->isActive());
    const MeshBvh bvh(doc->head());
    const Aabb box = boundsOf(doc->head());
    const glm::vec3 cheek_hs
        = bvh.closestPoint({ box.center().x + 0.03f, box.center().y - 0.02f, box.max.z + 0.05f }).point;
    const glm::vec2 pixel = view->project(glm::vec3(expected * glm::vec4(cheek_hs, 1.0f)));
    const QPoint at(static_cast<int>(std::lround(pixel.x)), static_cast<int>(std::lround(pixel.y)));
    const ViewRay ray = view->rayAt(at);
    const auto onTurned = headHit(bvh, ray, expected);
    ASSERT_TRUE(onTurned && glm::distance(*onTurned, cheek_hs) < 0.005f) << "the cheek is not in view";
    const auto onRest = headHit(bvh, ray, glm::mat4(1.0f));
    ASSERT_TRUE(!onRest || glm::distance(*onRest, cheek_hs) > 0.03f) << "the test cannot tell the two apart";

    // A click on the cheek paints it there (head space), and only there and at its mirror.
    const std::vector<float> before = doc->region(0).weights.toVector();
    const glm::vec3 near_hs = *onTurned;
    QTest::mouseClick(view, Qt::LeftButton, Qt::NoModifier, at);
    ASSERT_EQ(doc->undoStack()->count(), 1) << "the click did not paint";
    const std::vector<float> after = doc->region(0).weights.toVector();
    const float radius = window->paintTool()->settings().radiusMetres;
    const float plane = window->paintTool()->mirrorPlaneX();
    const glm::vec3 mirror_hs{ 2.0f * plane - near_hs.x, near_hs.y, near_hs.z };
    int raisedNear = 0;
    int changedElsewhere = 0;
    for (std::size_t v = 0; v < after.size(); ++v) {
        if (after[v] == before[v])
            continue;
        const glm::vec3 p = doc->head().positions[v];
        const bool near = glm::distance(p, near_hs) <= radius || glm::distance(p, mirror_hs) <= radius;
        raisedNear += near && after[v] > before[v] ? 1 : 0;
        changedElsewhere += near ? 0 : 1;
    }
    std::printf("[ moved    ] a click on the turned head's cheek raised %d vertices' weights near it; %d elsewhere\n",
        raisedNear, changedElsewhere);
    EXPECT_GE(raisedNear, 5);
    EXPECT_EQ(changedElsewhere, 0);

    // A pixel where the head at rest would be but the turned head is not: nothing painted.
    ASSERT_TRUE(stepUntilPlaced()) << "the viewport does not draw the head turned after the regroom";
    std::optional<QPoint> miss;
    for (int y = 60; y < view->height() - 60 && !miss; y += 6)
        for (int x = 60; x < view->width() - 60 && !miss; x += 6) {
            const ViewRay r = view->rayAt(QPoint(x, y));
            if (headHit(bvh, r, glm::mat4(1.0f)) && !headHit(bvh, r, expected))
                miss = QPoint(x, y);
        }
    ASSERT_TRUE(miss.has_value());
    QTest::mouseClick(view, Qt::LeftButton, Qt::NoModifier, *miss);
    EXPECT_EQ(doc->undoStack()->count(), 1) << "a click off the turned head painted";
    EXPECT_EQ(doc->region(0).weights.toVector(), after);
    doc->undoStack()->setClean(); // close without a prompt
}
