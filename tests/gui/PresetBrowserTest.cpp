// The preset browser on a real Document: the bundled presets are listed, applying one is one undo
// step, the artist's own presets are saved, listed, applied and deleted in a test-mode user folder,
// and a broken preset is shown greyed and cannot be applied.
#include "app/editor/PresetBrowser.h"
#include "app/editor/Document.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QListWidget>
#include <QPushButton>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QTest>
#include <QUndoStack>

#include <gtest/gtest.h>

#include <memory>
#include <ostream>
#include <set>
#include <vector>

using namespace wisp;

// Readable QStrings in failure messages.
QT_BEGIN_NAMESPACE
inline void PrintTo(const QString& s, std::ostream* os)
{
    *os << '"' << s.toStdString() << '"';
}
QT_END_NAMESPACE

namespace {

void showActive(QWidget* widget)
{
    widget->resize(420, 520);
    widget->show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(widget));
    widget->activateWindow();
    ASSERT_TRUE(QTest::qWaitForWindowActive(widget));
}

void click(QAbstractButton* button)
{
    ASSERT_NE(button, nullptr);
    ASSERT_TRUE(button->isEnabled());
    QTest::mouseClick(button, Qt::LeftButton);
}

void clickRow(QListWidget* list, int row)
{
    ASSERT_GE(row, 0);
    const QRect rect = list->visualItemRect(list->item(row));
    ASSERT_FALSE(rect.isEmpty());
    QTest::mouseClick(list->viewport(), Qt::LeftButton, Qt::NoModifier, rect.center());
    ASSERT_EQ(list->currentRow(), row);
}

// A bundled preset as the browser reads it.
io::Preset bundled(const QString& file)
{
    QFile f(QStringLiteral(":/presets/") + file);
    EXPECT_TRUE(f.open(QIODevice::ReadOnly)) << file.toStdString();
    io::Result<io::PresetReadResult> read = io::parsePreset(f.readAll().toStdString(), file.toStdString());
    EXPECT_TRUE(read.ok()) << (read.ok() ? "" : read.error().toString());
    return read.ok() ? read.value().preset : io::Preset{};
}

void writeFile(const QString& path, const QByteArray& text)
{
    ASSERT_TRUE(QDir().mkpath(QFileInfo(path).absolutePath()));
    QFile f(path);
    ASSERT_TRUE(f.open(QIODevice::WriteOnly | QIODevice::Truncate));
    ASSERT_EQ(f.write(text), text.size());
}

class PresetBrowserTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        // The user folder is a test folder, emptied for each test.
        QStandardPaths::setTestModeEnabled(true);
        QDir(PresetBrowser::userFolder()).removeRecursively();
        document = std::make_unique<Document>();
        browser = std::make_unique<PresetBrowser>(document.get());
        ASSERT_NO_FATAL_FAILURE(showActive(browser.get()));
    }
    void TearDown() override
    {
        browser.reset();
        QDir(PresetBrowser::userFolder()).removeRecursively();
    }

    QListWidget* list() const { return browser->listWidget(); }
    QUndoStack* undo() const { return document->undoStack(); }
    const GrowthRegion& current() const { return document->region(document->currentRegion()); }

    int rowNamed(const QString& name) const
    {
        for (int row = 0; row < list()->count(); ++row)
            if (list()->item(row)->text() == name)
                return row;
        return -1;
    }

    std::unique_ptr<Document> document;
    std::unique_ptr<PresetBrowser> browser;
};

} // namespace

TEST_F(PresetBrowserTest, ListsTheSixBundledPresetsByNameWithTheirDescriptions)
{
    ASSERT_EQ(list()->count(), 6); // the user folder is empty
    const QStringList expected = { QStringLiteral("Curly"), QStringLiteral("Short bob"), QStringLiteral("Straight"),
        QStringLiteral("Wavy"), QStringLiteral("Windy"), QStringLiteral("Zero gravity") };
    for (int row = 0; row < 6; ++row) {
        QListWidgetItem* item = list()->item(row);
        EXPECT_EQ(item->text(), expected[row]); // sorted by name
        EXPECT_TRUE(item->data(PresetBrowser::kBundledRole).toBool());
        EXPECT_TRUE(item->data(PresetBrowser::kErrorRole).toString().isEmpty()) << item->text().toStdString();
        EXPECT_FALSE(item->icon().isNull()); // the bundled mark
    }
    EXPECT_TRUE(list()->item(rowNamed(QStringLiteral("Curly")))->toolTip().contains(QStringLiteral("Tight ringlets")));
    // Nothing selected: nothing to apply or delete. (Showing the list focuses it, which makes
    // its first row current.)
    list()->setCurrentRow(-1);
    EXPECT_FALSE(browser->applyButton()->isEnabled());
    EXPECT_FALSE(browser->deleteButton()->isEnabled());
    EXPECT_TRUE(browser->saveButton()->isEnabled());
}

TEST_F(PresetBrowserTest, ApplyingCurlyIsOneUndoStepThatRestoresTheLookExactly)
{
    const io::Preset curly = bundled(QStringLiteral("curly.json"));
    ASSERT_EQ(curly.regions.size(), 1u);
    const double radius = curly.regions[0].wisp.get(Param::CurlRadius);
    const double turns = curly.regions[0].wisp.get(Param::CurlTurns);
    ASSERT_NE(current().values.get(Param::CurlRadius), radius);
    ASSERT_NE(current().values.get(Param::CurlTurns), turns);

    const ParameterValues parametersBefore = document->parameters();
    const std::vector<GrowthRegion> regionsBefore = document->regions();
    const int stepsBefore = undo()->count();
    QSignalSpy messages(browser.get(), &PresetBrowser::message);

    ASSERT_NO_FATAL_FAILURE(clickRow(list(), rowNamed(QStringLiteral("Curly"))));
    EXPECT_FALSE(browser->deleteButton()->isEnabled()); // bundled
    ASSERT_NO_FATAL_FAILURE(click(browser->applyButton()));

    EXPECT_EQ(current().values.get(Param::CurlRadius), radius);
    EXPECT_EQ(current().values.get(Param::CurlTurns), turns);
    EXPECT_EQ(document->parameters().get(Param::Segments), curly.parameters.get(Param::Segments));
    EXPECT_EQ(undo()->count(), stepsBefore + 1);
    ASSERT_EQ(messages.count(), 1);
    EXPECT_TRUE(messages.at(0).at(0).toString().contains(QStringLiteral("Curly")));

    undo()->undo();
    EXPECT_EQ(document->parameters(), parametersBefore);
    EXPECT_EQ(document->regions(), regionsBefore);
    undo()->redo();
    EXPECT_EQ(current().values.get(Param::CurlRadius), radius);
}

TEST_F(PresetBrowserTest, EnterOnARowAppliesIt)
{
    const io::Preset wavy = bundled(QStringLiteral("wavy.json"));
    ASSERT_NO_FATAL_FAILURE(clickRow(list(), rowNamed(QStringLiteral("Wavy"))));
    const int stepsBefore = undo()->count();
    QTest::keyClick(list(), Qt::Key_Return);
    EXPECT_EQ(undo()->count(), stepsBefore + 1);
    EXPECT_EQ(current().values.get(Param::CurlTurns), wavy.regions[0].wisp.get(Param::CurlTurns));
}

TEST_F(PresetBrowserTest, ASavedPresetIsListedAndBringsTheLookBack)
{
    ASSERT_EQ(document->editRegionParameter(document->currentRegion(), Param::CurlRadius, 0.02, false), QString());
    ASSERT_EQ(document->editRegionParameter(document->currentRegion(), Param::CurlTurns, 12.0, false), QString());
    ASSERT_EQ(document->editParameter(Param::Gravity, 3.5, false), QString());
    const ParameterValues savedParameters = document->parameters();
    const ParameterValues savedWisp = current().values;

    ASSERT_TRUE(browser->savePreset(QStringLiteral("My Look"), false));
    const QString path = PresetBrowser::userFolder() + QStringLiteral("/my-look.json");
    EXPECT_EQ(PresetBrowser::userPresetPath(QStringLiteral("My Look")), path);
    EXPECT_TRUE(QFileInfo::exists(path));
    ASSERT_EQ(list()->count(), 7);
    const int row = rowNamed(QStringLiteral("My Look"));
    ASSERT_EQ(row, 6); // after the bundled ones
    EXPECT_EQ(list()->currentRow(), row); // the new preset is selected
    EXPECT_FALSE(list()->item(row)->data(PresetBrowser::kBundledRole).toBool());
    EXPECT_EQ(list()->item(row)->data(PresetBrowser::kPathRole).toString(), path);
    EXPECT_TRUE(browser->deleteButton()->isEnabled());

    // Saving again under the same name asks first: refused without `overwrite`, done with it.
    EXPECT_FALSE(browser->savePreset(QStringLiteral("my look!"), false));
    EXPECT_TRUE(browser->savePreset(QStringLiteral("My Look"), true));
    EXPECT_EQ(list()->count(), 7);

    // Change the look, then apply the saved preset: it comes back.
    ASSERT_NO_FATAL_FAILURE(clickRow(list(), rowNamed(QStringLiteral("Curly"))));
    ASSERT_NO_FATAL_FAILURE(click(browser->applyButton()));
    ASSERT_EQ(document->editParameter(Param::Gravity, 1.0, false), QString());
    ASSERT_NE(current().values, savedWisp);
    ASSERT_NE(document->parameters(), savedParameters);

    ASSERT_NO_FATAL_FAILURE(clickRow(list(), rowNamed(QStringLiteral("My Look"))));
    ASSERT_NO_FATAL_FAILURE(click(browser->applyButton()));
    EXPECT_EQ(document->parameters(), savedParameters);
    EXPECT_EQ(current().values, savedWisp);
}

TEST_F(PresetBrowserTest, AnEmptyNameIsRefused)
{
    QSignalSpy messages(browser.get(), &PresetBrowser::message);
    EXPECT_FALSE(browser->savePreset(QStringLiteral("   "), true));
    EXPECT_EQ(messages.count(), 1);
    EXPECT_EQ(list()->count(), 6);
    EXPECT_TRUE(QDir(PresetBrowser::userFolder()).entryList({ QStringLiteral("*.json") }, QDir::Files).isEmpty());
}

TEST_F(PresetBrowserTest, NamesBecomeSafeFileNames)
{
    const QString folder = PresetBrowser::userFolder() + QLatin1Char('/');
    EXPECT_EQ(
        PresetBrowser::userPresetPath(QStringLiteral("../../etc/passwd")), folder + QStringLiteral("etc-passwd.json"));
    EXPECT_EQ(
        PresetBrowser::userPresetPath(QStringLiteral("  Wet: look?  ")), folder + QStringLiteral("wet-look.json"));
    EXPECT_EQ(PresetBrowser::userPresetPath(QStringLiteral("???")), folder + QStringLiteral("preset.json"));
    EXPECT_EQ(PresetBrowser::userPresetPath(QStringLiteral("Con")), folder + QStringLiteral("con-preset.json"));
    EXPECT_EQ(
        PresetBrowser::userPresetPath(QStringLiteral("Böse Locken")), folder + QStringLiteral("böse-locken.json"));
}

TEST_F(PresetBrowserTest, ABrokenPresetIsGreyedWithItsErrorAndCannotBeApplied)
{
    writeFile(PresetBrowser::userFolder() + QStringLiteral("/bad.json"),
        R"({"format": "wisp-preset", "version": 2, "name": "Bad",
                  "regions": [{"name": "A", "clump_degree": 3.0}]})");
    ASSERT_NO_FATAL_FAILURE(click(browser->refreshButton()));
    ASSERT_EQ(list()->count(), 7);
    const int row = rowNamed(QStringLiteral("bad")); // it has no name to show but its file's
    ASSERT_EQ(row, 6);
    QListWidgetItem* item = list()->item(row);
    EXPECT_TRUE(item->toolTip().contains(QStringLiteral("regions[0].clump_degree"))) << item->toolTip().toStdString();
    EXPECT_TRUE(item->data(PresetBrowser::kErrorRole).toString().contains(QStringLiteral("regions[0].clump_degree")));
    EXPECT_EQ(item->foreground().color(), list()->palette().color(QPalette::Disabled, QPalette::Text));

    const ParameterValues parametersBefore = document->parameters();
    const std::vector<GrowthRegion> regionsBefore = document->regions();
    const int stepsBefore = undo()->count();
    const int indexBefore = undo()->index();

    ASSERT_NO_FATAL_FAILURE(clickRow(list(), row));
    EXPECT_FALSE(browser->applyButton()->isEnabled());
    EXPECT_TRUE(browser->deleteButton()->isEnabled()); // a broken user preset can still go
    QTest::mouseClick(browser->applyButton(), Qt::LeftButton);
    QTest::keyClick(list(), Qt::Key_Return);
    EXPECT_FALSE(browser->applyPreset(row));

    EXPECT_EQ(document->parameters(), parametersBefore);
    EXPECT_EQ(document->regions(), regionsBefore);
    EXPECT_EQ(undo()->count(), stepsBefore);
    EXPECT_EQ(undo()->index(), indexBefore);
}

TEST_F(PresetBrowserTest, LoadingWarningsAreReportedWhenThePresetIsApplied)
{
    writeFile(PresetBrowser::userFolder() + QStringLiteral("/shiny.json"),
        R"({"format": "wisp-preset", "version": 2, "name": "Shiny",
                  "regions": [{"name": "A", "wisp": {"length": 0.3, "sheen": 1.0}}]})");
    browser->refresh();
    const int row = rowNamed(QStringLiteral("Shiny"));
    ASSERT_EQ(row, 6);
    QSignalSpy messages(browser.get(), &PresetBrowser::message);
    ASSERT_TRUE(browser->applyPreset(row));
    EXPECT_DOUBLE_EQ(current().values.get(Param::Length), 0.3);
    ASSERT_EQ(messages.count(), 1);
    EXPECT_TRUE(messages.at(0).at(0).toString().contains(QStringLiteral("regions[0].wisp.sheen")))
        << messages.at(0).at(0).toString().toStdString();
}

TEST_F(PresetBrowserTest, DeletingAUserPresetRemovesItsFileAndRow)
{
    ASSERT_TRUE(browser->savePreset(QStringLiteral("Gone Soon"), false));
    const QString path = PresetBrowser::userPresetPath(QStringLiteral("Gone Soon"));
    ASSERT_TRUE(QFileInfo::exists(path));
    const int row = rowNamed(QStringLiteral("Gone Soon"));
    ASSERT_GE(row, 0);

    EXPECT_TRUE(browser->deletePreset(row));
    EXPECT_FALSE(QFileInfo::exists(path));
    EXPECT_EQ(rowNamed(QStringLiteral("Gone Soon")), -1);
    EXPECT_EQ(list()->count(), 6);
}

TEST_F(PresetBrowserTest, BundledPresetsCannotBeDeleted)
{
    for (int row = 0; row < 6; ++row) {
        ASSERT_NO_FATAL_FAILURE(clickRow(list(), row));
        EXPECT_FALSE(browser->deleteButton()->isEnabled()) << row;
        EXPECT_TRUE(browser->applyButton()->isEnabled()) << row;
        EXPECT_FALSE(browser->deletePreset(row));
    }
    EXPECT_EQ(list()->count(), 6);
}
