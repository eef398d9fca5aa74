// The growth area Wisp makes for an imported head (sim/groom/GrowthMap.h's scalpGrowth) is the scalp,
// on the real heads as the importer places them: no root on the face or below the nose line, and
// the crown and the back of the skull covered. Landmarks are measured here, on the placed mesh.
#include "IoTestSupport.h"
#include "io/HeadPlacement.h"
#include "io/MeshReader.h"
#include "sim/groom/Groom.h"
#include "sim/groom/GrowthMap.h"
#include "sim/params/Parameters.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>

using namespace wisp;
using namespace wisp::io;
using wisp::test::assetPath;

TEST(ScalpGrowth, RootsGrowOnTheScalpOfEverySharedHead)
{
    for (const char* name : { "heads/max_planck_decimated.obj", "heads/igea_tristrips.ply", "heads/cy_woman_head.ply",
             "hair/ct2hair_bangs_head.ply" }) {
        const auto path = assetPath(name);
        REQUIRE_ASSET(path);
        Result<MeshReadResult> read = readMesh(path.string());
        ASSERT_TRUE(read.ok()) << read.error().toString();
        TriangleMesh head = std::move(read).value().mesh;
        placeHead(head);
        const std::vector<float> weights = scalpGrowth(head);

        // Landmarks: the top, the nose tip (front-most within 1 cm of the middle), the back of the skull.
        const Aabb box = boundsOf(head);
        glm::vec3 nose(0.0f, 0.0f, std::numeric_limits<float>::lowest());
        for (const glm::vec3& p : head.positions)
            if (std::abs(p.x - box.center().x) < 0.01f && p.y > box.max.y - 0.3f && p.z > nose.z)
                nose = p;
        const float top = box.max.y, height = top - nose.y;
        float back = nose.z;
        for (const glm::vec3& p : head.positions)
            if (p.y > nose.y)
                back = std::min(back, p.z);
        const float depth = nose.z - back;
        ASSERT_GT(height, 0.05f) << name;

        GroomSettings settings = groomSettingsFrom(ParameterValues{});
        settings.densityPerCm2 = 2.0f;
        const GroomResult grown = buildGroom(head, weights, settings);
        ASSERT_TRUE(grown.ok()) << grown.error;
        ASSERT_GT(grown.groom.strandCount(), 50u) << name;
        // Heights of the lowest roots, in nose-to-top heights above the nose tip: anywhere, in the
        // front half (temples, cheeks, eyes) and in the front quarter (forehead, eyes, nose).
        float lowest = std::numeric_limits<float>::max(), lowestFrontHalf = lowest, lowestOnFace = lowest;
        for (const SurfacePoint& root : grown.groom.roots) {
            const glm::vec3 p = pointOn(head, root);
            const float above = (p.y - nose.y) / height;
            lowest = std::min(lowest, above);
            if (p.z > nose.z - 0.5f * depth)
                lowestFrontHalf = std::min(lowestFrontHalf, above);
            if (p.z > nose.z - 0.25f * depth)
                lowestOnFace = std::min(lowestOnFace, above);
        }
        // The brows are about 0.4 of the nose-to-top height above the nose tip, the eyes about 0.25.
        EXPECT_GT(lowestOnFace, 0.5f) << name << ": a root on the forehead below the hairline, or lower";
        EXPECT_GT(lowestFrontHalf, 0.35f) << name << ": a root at the eyes' height or below, at the front";
        EXPECT_GT(lowest, -0.2f) << name << ": a root on the neck or the bust";

        // The crown (top tenth) and the back of the skull (rear tenth, from the ears' top to the
        // hairline's height) are covered.
        std::size_t crown = 0, crownCovered = 0, rear = 0, rearCovered = 0;
        for (std::size_t i = 0; i < head.positions.size(); ++i) {
            const glm::vec3& p = head.positions[i];
            if (p.y > top - 0.1f * height) {
                ++crown;
                crownCovered += weights[i] > 0.9f;
            }
            if (p.z < back + 0.1f * depth && p.y > nose.y + 0.3f * height && p.y < nose.y + 0.7f * height) {
                ++rear;
                rearCovered += weights[i] > 0.9f;
            }
        }
        ASSERT_GT(crown, 0u);
        ASSERT_GT(rear, 0u) << name;
        EXPECT_EQ(crownCovered, crown) << name;
        EXPECT_GE(double(rearCovered), 0.95 * double(rear)) << name;
        std::cout << "[          ] " << name << ": " << grown.groom.strandCount() << " roots; lowest on the face "
                  << lowestOnFace << ", in the front half " << lowestFrontHalf << ", anywhere " << lowest
                  << " (nose-to-top heights above the nose tip, " << height << " m); crown " << crownCovered << "/"
                  << crown << ", back " << rearCovered << "/" << rear << " vertices covered\n";
    }
}
