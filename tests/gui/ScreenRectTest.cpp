// clipRectOfBox: the part of the viewport a box's projection covers (HairLowResTarget's region).

#include "widgets/ScreenRect.h"

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

#include <gtest/gtest.h>

#include <limits>

namespace wisp {
namespace {

// A camera at z = 1 m looking down -z with a 90 degree vertical field of view, square viewport.
glm::mat4 cameraAtOneMetre()
{
    const glm::mat4 view = glm::lookAt(glm::vec3(0.0f, 0.0f, 1.0f), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    return glm::perspective(glm::radians(90.0f), 1.0f, 0.01f, 10.0f) * view;
}

TEST(ScreenRectTest, ABoxInFrontCoversItsProjectionWidenedByTheMargin)
{
    // A 0.2 m cube centred 1 m in front: its near face (0.9 m away) spans +-0.1 / 0.9 in NDC.
    const Aabb box{ glm::vec3(-0.1f), glm::vec3(0.1f) };
    const glm::vec2 viewport(400.0f, 400.0f);
    const ClipRect tight = clipRectOfBox(box, cameraAtOneMetre(), viewport, 0.0f);
    const float near = 0.1f / 0.9f;
    EXPECT_NEAR(tight.x, -near, 1e-4f);
    EXPECT_NEAR(tight.y, -near, 1e-4f);
    EXPECT_NEAR(tight.z, near, 1e-4f);
    EXPECT_NEAR(tight.w, near, 1e-4f);
    // Ten pixels of a 400-pixel viewport are 0.05 in clip space.
    const ClipRect wide = clipRectOfBox(box, cameraAtOneMetre(), viewport, 10.0f);
    EXPECT_NEAR(wide.x, -near - 0.05f, 1e-4f);
    EXPECT_NEAR(wide.w, near + 0.05f, 1e-4f);
    EXPECT_FALSE(clipRectEmpty(wide));
}

TEST(ScreenRectTest, ABoxReachingBehindTheCameraTakesTheWholeViewport)
{
    // From 0.5 m in front to 0.5 m behind the camera: no bound but the viewport.
    const Aabb box{ glm::vec3(-0.1f, -0.1f, 0.5f), glm::vec3(0.1f, 0.1f, 1.5f) };
    const ClipRect rect = clipRectOfBox(box, cameraAtOneMetre(), glm::vec2(400.0f), 2.0f);
    EXPECT_EQ(rect, kWholeViewport);
    // Not finite: the whole viewport too, never a rectangle made of NaNs.
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(clipRectOfBox(Aabb{ glm::vec3(nan), glm::vec3(0.1f) }, cameraAtOneMetre(), glm::vec2(400.0f), 2.0f),
        kWholeViewport);
}

TEST(ScreenRectTest, ABoxPartlyOffScreenIsClippedAndOneWhollyOffScreenIsEmpty)
{
    const glm::vec2 viewport(400.0f, 300.0f);
    // Centred 2 m to the right, 1 m in front: its projection starts past the right edge.
    const Aabb outside{ glm::vec3(1.9f, -0.1f, -0.1f), glm::vec3(2.1f, 0.1f, 0.1f) };
    EXPECT_TRUE(clipRectEmpty(clipRectOfBox(outside, cameraAtOneMetre(), viewport, 4.0f)));
    // Straddling the right edge: cut at x = 1.
    const Aabb straddling{ glm::vec3(0.8f, -0.1f, -0.1f), glm::vec3(1.2f, 0.1f, 0.1f) };
    const ClipRect rect = clipRectOfBox(straddling, cameraAtOneMetre(), viewport, 4.0f);
    EXPECT_FLOAT_EQ(rect.z, 1.0f);
    EXPECT_NEAR(rect.x, 0.8f / 1.1f - 8.0f / 400.0f, 1e-4f); // its far face, widened by 4 of 400 pixels
    EXPECT_GT(rect.w, rect.y);
    // Widening keeps within the viewport and leaves an empty rectangle empty.
    EXPECT_EQ(widenClipRect(kWholeViewport, viewport, 50.0f), kWholeViewport);
    EXPECT_TRUE(clipRectEmpty(widenClipRect(ClipRect(0.0f), viewport, 50.0f)));
}

} // namespace
} // namespace wisp
