#pragma once
// A viewport in the editor's default view (585 x 710, between its docks) showing the default groom,
// draped once for the whole test suite (the drape is the slow part). Shared by the display-density
// and half-resolution hair tests.

#include "GuiTestSupport.h"

#include "app/editor/Document.h"
#include "app/editor/SettledScene.h"
#include "sim/geometry/Body.h"
#include "widgets/Viewport.h"

#include <gtest/gtest.h>

#include <memory>

namespace wisp::test {

class SettledViewportTest : public ::testing::Test {
protected:
    static void SetUpTestSuite()
    {
        Document document;
        const SceneToSettle scene{ document.head(), document.regions(), document.soloRegion(), document.parameters(),
            {} };
        settled = new SettledFrame(settleScene(scene, 0, 2));
        head = new TriangleMesh(document.head());
    }
    static void TearDownTestSuite()
    {
        delete settled;
        settled = nullptr;
        delete head;
        head = nullptr;
    }
    void SetUp() override
    {
        ASSERT_TRUE(settled->frame) << settled->error;
        viewport = std::make_unique<Viewport>();
        viewport->resize(585, 710);
        viewport->setHead(*head);
        viewport->setBody(defaultBody(*head));
        viewport->setShowGrowthOverlay(false);
        viewport->setShowGrid(false);
        viewport->setFrame(settled->frame);
    }
    static inline SettledFrame* settled = nullptr;
    static inline TriangleMesh* head = nullptr;
    std::unique_ptr<Viewport> viewport;
};

} // namespace wisp::test
