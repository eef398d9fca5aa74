// The presets panel's thumbnails: made for every bundled preset while the panel is on screen,
// cached on disk (a second browser reads them without rendering), and made anew when the artist
// saves a preset over an old one.

#include "GuiTestSupport.h"

#include "app/editor/Document.h"
#include "app/editor/PresetBrowser.h"
#include "app/editor/PresetThumbnails.h"

#include <QDir>
#include <QImage>
#include <QListWidget>

namespace wisp {
namespace {

// Making a thumbnail grooms and drapes a head on one thread: allow for a slow, busy machine.
constexpr int kThumbnailWaitMs = 120000 * WISP_SLOW_BUILD_FACTOR;

QImage thumbnailOf(const PresetBrowser& browser, int row)
{
    if (row < 0 || row >= browser.listWidget()->count())
        return {};
    return browser.listWidget()->item(row)->data(PresetBrowser::kThumbnailRole).value<QImage>();
}

int rowOf(const PresetBrowser& browser, const QString& text)
{
    for (int row = 0; row < browser.listWidget()->count(); ++row)
        if (browser.listWidget()->item(row)->text() == text)
            return row;
    return -1;
}

// Mean green minus red over the image: how green its hair is.
double greenness(const QImage& image)
{
    double sum = 0.0;
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
            const QRgb p = image.pixel(x, y);
            sum += qGreen(p) - qRed(p);
        }
    return sum / (image.width() * image.height());
}

class PresetThumbnailsTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        QStandardPaths::setTestModeEnabled(true);
        QDir(PresetBrowser::userFolder()).removeRecursively();
        QDir(PresetThumbnails::cacheFolder()).removeRecursively();
    }
    void TearDown() override { QDir(PresetBrowser::userFolder()).removeRecursively(); }
    Document document;
};

TEST_F(PresetThumbnailsTest, EveryBundledPresetGetsOneAndTheCacheServesTheNextBrowser)
{
    {
        PresetBrowser browser(&document);
        const int rows = browser.listWidget()->count();
        ASSERT_GE(rows, 6);
        EXPECT_TRUE(thumbnailOf(browser, 0).isNull()); // nothing cached, nothing made while hidden
        browser.show();
        ASSERT_TRUE(test::waitUntil(
            [&] {
                for (int row = 0; row < rows; ++row)
                    if (thumbnailOf(browser, row).isNull())
                        return false;
                return true;
            },
            kThumbnailWaitMs));
        EXPECT_EQ(browser.thumbnails()->made(), rows);
        const QImage curly = thumbnailOf(browser, rowOf(browser, QStringLiteral("Curly")));
        const QImage bob = thumbnailOf(browser, rowOf(browser, QStringLiteral("Short bob")));
        EXPECT_EQ(curly.size(), QSize(PresetThumbnails::kSidePixels, PresetThumbnails::kSidePixels));
        EXPECT_NE(curly, bob);
        EXPECT_FALSE(browser.listWidget()->item(0)->icon().isNull());
        EXPECT_EQ(QDir(PresetThumbnails::cacheFolder()).entryList({ "*.png" }, QDir::Files).size(), rows);
    }
    // A new browser finds them all in the cache at once, hidden, rendering nothing.
    PresetBrowser again(&document);
    for (int row = 0; row < again.listWidget()->count(); ++row)
        EXPECT_FALSE(thumbnailOf(again, row).isNull()) << row;
    EXPECT_EQ(again.thumbnails()->made(), 0);
    EXPECT_FALSE(again.thumbnails()->busy());
}

TEST_F(PresetThumbnailsTest, SavingAPresetAgainRefreshesItsThumbnail)
{
    PresetBrowser browser(&document);
    browser.show();
    ASSERT_TRUE(browser.savePreset(QStringLiteral("Mine"), false));
    const auto mine = [&] { return thumbnailOf(browser, rowOf(browser, QStringLiteral("Mine"))); };
    ASSERT_TRUE(test::waitUntil([&] { return !mine().isNull(); }, kThumbnailWaitMs));
    const QImage before = mine();

    document.setRegionColours(0, glm::vec3(0.05f, 0.6f, 0.08f), glm::vec3(0.1f, 0.7f, 0.1f));
    ASSERT_TRUE(browser.savePreset(QStringLiteral("Mine"), true));
    ASSERT_TRUE(test::waitUntil([&] { return !mine().isNull() && mine() != before; }, kThumbnailWaitMs));
    EXPECT_GT(greenness(mine()), greenness(before) + 1.0);
    EXPECT_EQ(QDir(PresetThumbnails::cacheFolder()).entryList({ "*.png" }, QDir::Files).size(),
        QDir(":/presets").entryList({ "*.json" }).size() + 2); // the bundled ones made meanwhile, and both of Mine's
}

} // namespace
} // namespace wisp
