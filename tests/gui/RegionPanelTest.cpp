// The region and wisp panels as an artist uses them: real widgets on a real Document, driven by
// mouse and key events, every edit checked in the document and through undo and redo.
#include "app/editor/RegionPanel.h"
#include "GuiTestSupport.h"
#include "app/editor/Document.h"
#include "app/editor/WispPanel.h"
#include "widgets/ParameterPanel.h"

#include <QApplication>
#include <QColorDialog>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QPushButton>
#include <QSlider>
#include <QStandardPaths>
#include <QStyleOptionSlider>
#include <QStyleOptionViewItem>
#include <QTest>
#include <QToolButton>
#include <QUndoStack>

#include <gtest/gtest.h>

#include <memory>
#include <ostream>
#include <set>
#include <vector>

using namespace wisp;
using wisp::test::dragSliderHandle;
using wisp::test::typeValue;

// Readable QStrings in failure messages.
QT_BEGIN_NAMESPACE
inline void PrintTo(const QString& s, std::ostream* os)
{
    *os << '"' << s.toStdString() << '"';
}
QT_END_NAMESPACE

namespace {

// --- Helpers: what an artist does ---------------------------------------------------------------

void click(QAbstractButton* button)
{
    ASSERT_NE(button, nullptr);
    ASSERT_TRUE(button->isEnabled());
    QTest::mouseClick(button, Qt::LeftButton);
}

void clickRow(QListWidget* list, int row)
{
    const QRect rect = list->visualItemRect(list->item(row));
    ASSERT_FALSE(rect.isEmpty());
    QTest::mouseClick(list->viewport(), Qt::LeftButton, Qt::NoModifier, rect.center());
}

// Where the row's check box is drawn: the rectangle the item delegate tests a click against.
QPoint checkBoxCentre(QListWidget* list, int row)
{
    QListWidgetItem* item = list->item(row);
    QStyleOptionViewItem option;
    option.initFrom(list->viewport());
    option.rect = list->visualItemRect(item);
    option.features = QStyleOptionViewItem::HasCheckIndicator | QStyleOptionViewItem::HasDisplay
        | QStyleOptionViewItem::HasDecoration;
    option.checkState = item->checkState();
    option.text = item->text();
    option.icon = item->icon();
    option.decorationSize = list->iconSize();
    option.viewItemPosition = QStyleOptionViewItem::OnlyOne;
    return list->style()->subElementRect(QStyle::SE_ItemViewItemCheckIndicator, &option, list).center();
}

// The name editor the list has open, if any (a closed one lingers until it is deleted).
QLineEdit* openNameEditor(QListWidget* list)
{
    for (QLineEdit* editor : list->findChildren<QLineEdit*>())
        if (editor->isVisible())
            return editor;
    return nullptr;
}

// Select all, type, Enter. The view commits the name from its event loop, as it would for the artist.
void typeName(QListWidget* list, QLineEdit* editor, const QString& text)
{
    QTest::keyClick(editor, Qt::Key_A, Qt::ControlModifier);
    if (text.isEmpty())
        QTest::keyClick(editor, Qt::Key_Backspace);
    else
        QTest::keyClicks(editor, text);
    QTest::keyClick(editor, Qt::Key_Return);
    EXPECT_TRUE(QTest::qWaitFor([&] { return openNameEditor(list) == nullptr; }, 2000))
        << "the name editor stayed open";
}

// F2 on the list opens the name editor on the current row.
void renameCurrentRow(QListWidget* list, const QString& text)
{
    list->setFocus();
    QTest::keyClick(list, Qt::Key_F2);
    QLineEdit* editor = openNameEditor(list);
    ASSERT_NE(editor, nullptr) << "F2 opened no name editor";
    typeName(list, editor, text);
}

std::vector<std::uint32_t> documentIds(const Document& document)
{
    std::vector<std::uint32_t> ids;
    for (const GrowthRegion& r : document.regions())
        ids.push_back(r.id);
    return ids;
}

std::vector<std::uint32_t> rowIds(QListWidget* list)
{
    std::vector<std::uint32_t> ids;
    for (int row = 0; row < list->count(); ++row)
        ids.push_back(list->item(row)->data(RegionPanel::kRegionIdRole).value<std::uint32_t>());
    return ids;
}

std::vector<QString> rowNames(QListWidget* list)
{
    std::vector<QString> names;
    for (int row = 0; row < list->count(); ++row)
        names.push_back(list->item(row)->text());
    return names;
}

std::vector<QString> documentNames(const Document& document)
{
    std::vector<QString> names;
    for (const GrowthRegion& r : document.regions())
        names.push_back(QString::fromStdString(r.name));
    return names;
}

// Shows a panel as its own window and makes it active, so that keys reach it (Xvfb has no window
// manager to activate it).
void showActive(QWidget* widget)
{
    widget->resize(420, 520);
    widget->show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(widget));
    widget->activateWindow();
    ASSERT_TRUE(QTest::qWaitForWindowActive(widget));
}

// --- Region panel -------------------------------------------------------------------------------

class RegionPanelTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        // Keep the artist's real settings out of the tests.
        QStandardPaths::setTestModeEnabled(true);
        document = std::make_unique<Document>();
        panel = std::make_unique<RegionPanel>(document.get());
        ASSERT_NO_FATAL_FAILURE(showActive(panel.get()));
    }
    QListWidget* list() const { return panel->listWidget(); }
    QUndoStack* undo() const { return document->undoStack(); }

    // The rows show exactly the document: names, ids, visibility, solo and the current row.
    void expectRowsMatchDocument() const
    {
        ASSERT_EQ(list()->count(), document->regionCount());
        EXPECT_EQ(rowNames(list()), documentNames(*document));
        EXPECT_EQ(rowIds(list()), documentIds(*document));
        for (int row = 0; row < document->regionCount(); ++row) {
            const GrowthRegion& r = document->region(row);
            EXPECT_EQ(list()->item(row)->checkState(), r.visible ? Qt::Checked : Qt::Unchecked) << "row " << row;
            EXPECT_EQ(list()->item(row)->data(RegionPanel::kSoloRole).toBool(), r.id == document->soloRegion())
                << "row " << row;
        }
        EXPECT_EQ(list()->currentRow(), document->currentRegion());
    }

    // Adds regions with the Add button until there are `count`.
    void addUntil(int count)
    {
        while (document->regionCount() < count)
            ASSERT_NO_FATAL_FAILURE(click(panel->addButton()));
    }

    std::unique_ptr<Document> document;
    std::unique_ptr<RegionPanel> panel; // destroyed before the document it watches
};

TEST_F(RegionPanelTest, StartsWithTheDocumentsOneRegionSelected)
{
    ASSERT_EQ(document->regionCount(), 1);
    expectRowsMatchDocument();
    EXPECT_EQ(list()->currentRow(), 0);
    EXPECT_FALSE(panel->removeButton()->isEnabled());
    EXPECT_FALSE(panel->upButton()->isEnabled());
    EXPECT_FALSE(panel->downButton()->isEnabled());
    EXPECT_TRUE(panel->addButton()->isEnabled());
    EXPECT_FALSE(panel->soloButton()->isChecked());
    for (QToolButton* b :
        { panel->addButton(), panel->removeButton(), panel->upButton(), panel->downButton(), panel->soloButton() })
        EXPECT_FALSE(b->toolTip().isEmpty()) << b->objectName().toStdString();
}

TEST_F(RegionPanelTest, AddCreatesASecondRegionWithAUniqueNameAndSelectsIt)
{
    const std::uint32_t firstId = document->region(0).id;
    ASSERT_NO_FATAL_FAILURE(click(panel->addButton()));
    ASSERT_EQ(document->regionCount(), 2);
    EXPECT_EQ(document->currentRegion(), 1);
    EXPECT_EQ(document->region(0).id, firstId);
    EXPECT_NE(document->region(1).id, firstId);
    EXPECT_NE(document->region(1).name, document->region(0).name);
    EXPECT_TRUE(panel->removeButton()->isEnabled());
    expectRowsMatchDocument();
    EXPECT_EQ(undo()->count(), 1);

    // A third one gets yet another name, even after a rename took the obvious one.
    document->renameRegion(0, QStringLiteral("Region 3"));
    ASSERT_NO_FATAL_FAILURE(click(panel->addButton()));
    ASSERT_EQ(document->regionCount(), 3);
    const auto names = documentNames(*document);
    EXPECT_EQ(std::set<QString>(names.begin(), names.end()).size(), 3u);

    undo()->undo();
    undo()->undo();
    undo()->undo();
    EXPECT_EQ(document->regionCount(), 1);
    expectRowsMatchDocument();
    undo()->redo();
    EXPECT_EQ(document->regionCount(), 2);
    expectRowsMatchDocument();
}

TEST_F(RegionPanelTest, ClickingARowMakesItCurrentAndTheDocumentsCurrentIsShown)
{
    ASSERT_NO_FATAL_FAILURE(addUntil(3));
    ASSERT_NO_FATAL_FAILURE(clickRow(list(), 0));
    EXPECT_EQ(document->currentRegion(), 0);
    EXPECT_FALSE(panel->upButton()->isEnabled());
    EXPECT_TRUE(panel->downButton()->isEnabled());
    ASSERT_NO_FATAL_FAILURE(clickRow(list(), 2));
    EXPECT_EQ(document->currentRegion(), 2);
    EXPECT_FALSE(panel->downButton()->isEnabled());
    // Selection is not an edit.
    EXPECT_EQ(undo()->count(), 2);
    // And the other way: the brush or another panel selects a region.
    document->setCurrentRegion(1);
    EXPECT_EQ(list()->currentRow(), 1);
    EXPECT_TRUE(list()->item(1)->isSelected());
}

TEST_F(RegionPanelTest, F2RenamesTheRegionAndUndoRestoresTheName)
{
    const std::string before = document->region(0).name;
    ASSERT_NO_FATAL_FAILURE(renameCurrentRow(list(), QStringLiteral("Fringe")));
    EXPECT_EQ(document->region(0).name, "Fringe");
    EXPECT_EQ(list()->item(0)->text(), QStringLiteral("Fringe"));
    EXPECT_EQ(undo()->count(), 1);
    undo()->undo();
    EXPECT_EQ(document->region(0).name, before);
    expectRowsMatchDocument();
    undo()->redo();
    EXPECT_EQ(document->region(0).name, "Fringe");
    expectRowsMatchDocument();
}

TEST_F(RegionPanelTest, DoubleClickRenamesToo)
{
    const QRect rect = list()->visualItemRect(list()->item(0));
    // Qt 6's mouseDClick sends the double-click event alone; a real one follows a click and a press.
    QTest::mouseClick(list()->viewport(), Qt::LeftButton, Qt::NoModifier, rect.center());
    QTest::mousePress(list()->viewport(), Qt::LeftButton, Qt::NoModifier, rect.center());
    QTest::mouseDClick(list()->viewport(), Qt::LeftButton, Qt::NoModifier, rect.center());
    QTest::mouseRelease(list()->viewport(), Qt::LeftButton, Qt::NoModifier, rect.center());
    QLineEdit* editor = openNameEditor(list());
    ASSERT_NE(editor, nullptr) << "double-click opened no name editor";
    typeName(list(), editor, QStringLiteral("Crown"));
    EXPECT_EQ(document->region(0).name, "Crown");
    expectRowsMatchDocument();
}

TEST_F(RegionPanelTest, AnEmptyNameIsRefusedAndTheOldNameShownAgain)
{
    const std::string before = document->region(0).name;
    ASSERT_NO_FATAL_FAILURE(renameCurrentRow(list(), QString()));
    EXPECT_EQ(document->region(0).name, before);
    EXPECT_EQ(list()->item(0)->text(), QString::fromStdString(before));
    EXPECT_EQ(undo()->count(), 0);
    // Blanks alone are no name either.
    ASSERT_NO_FATAL_FAILURE(renameCurrentRow(list(), QStringLiteral("   ")));
    EXPECT_EQ(document->region(0).name, before);
    EXPECT_EQ(list()->item(0)->text(), QString::fromStdString(before));
    EXPECT_EQ(undo()->count(), 0);
}

TEST_F(RegionPanelTest, UpAndDownReorderRegionsWhoKeepTheirIdentity)
{
    ASSERT_NO_FATAL_FAILURE(addUntil(3));
    const std::vector<std::uint32_t> original = documentIds(*document);
    const std::uint32_t a = original[0], b = original[1], c = original[2];
    ASSERT_EQ(document->currentRegion(), 2);

    ASSERT_NO_FATAL_FAILURE(click(panel->upButton()));
    EXPECT_EQ(documentIds(*document), (std::vector<std::uint32_t>{ a, c, b }));
    EXPECT_EQ(document->currentRegion(), 1); // the selection stays on the moved region
    expectRowsMatchDocument();
    ASSERT_NO_FATAL_FAILURE(click(panel->upButton()));
    EXPECT_EQ(documentIds(*document), (std::vector<std::uint32_t>{ c, a, b }));
    EXPECT_EQ(document->currentRegion(), 0);
    EXPECT_FALSE(panel->upButton()->isEnabled());
    expectRowsMatchDocument();
    ASSERT_NO_FATAL_FAILURE(click(panel->downButton()));
    EXPECT_EQ(documentIds(*document), (std::vector<std::uint32_t>{ a, c, b }));
    expectRowsMatchDocument();

    const int steps = undo()->count();
    undo()->undo();
    EXPECT_EQ(documentIds(*document), (std::vector<std::uint32_t>{ c, a, b }));
    expectRowsMatchDocument();
    undo()->undo();
    undo()->undo();
    EXPECT_EQ(documentIds(*document), original);
    expectRowsMatchDocument();
    undo()->redo();
    EXPECT_EQ(documentIds(*document), (std::vector<std::uint32_t>{ a, c, b }));
    expectRowsMatchDocument();
    EXPECT_EQ(undo()->count(), steps);
}

TEST_F(RegionPanelTest, ClickingTheCheckBoxHidesAndShowsTheRegion)
{
    ASSERT_NO_FATAL_FAILURE(addUntil(2));
    QTest::mouseClick(list()->viewport(), Qt::LeftButton, Qt::NoModifier, checkBoxCentre(list(), 0));
    EXPECT_FALSE(document->region(0).visible);
    EXPECT_TRUE(document->region(1).visible);
    expectRowsMatchDocument();
    EXPECT_EQ(undo()->count(), 2);
    undo()->undo();
    EXPECT_TRUE(document->region(0).visible);
    expectRowsMatchDocument();
    undo()->redo();
    EXPECT_FALSE(document->region(0).visible);
    expectRowsMatchDocument();
    QTest::mouseClick(list()->viewport(), Qt::LeftButton, Qt::NoModifier, checkBoxCentre(list(), 0));
    EXPECT_TRUE(document->region(0).visible);
    expectRowsMatchDocument();
}

TEST_F(RegionPanelTest, SpaceTogglesTheCurrentRowsVisibility)
{
    list()->setFocus();
    QTest::keyClick(list(), Qt::Key_Space);
    EXPECT_FALSE(document->region(0).visible);
    expectRowsMatchDocument();
    undo()->undo();
    EXPECT_TRUE(document->region(0).visible);
    expectRowsMatchDocument();
}

TEST_F(RegionPanelTest, SoloGrowsOnlyTheCurrentRegionAndMarksItsRow)
{
    ASSERT_NO_FATAL_FAILURE(addUntil(2));
    ASSERT_EQ(document->currentRegion(), 1);
    const std::uint32_t soloId = document->region(1).id;
    ASSERT_NO_FATAL_FAILURE(click(panel->soloButton()));
    EXPECT_EQ(document->soloRegion(), soloId);
    EXPECT_TRUE(panel->soloButton()->isChecked());
    EXPECT_TRUE(list()->item(1)->data(RegionPanel::kSoloRole).toBool());
    EXPECT_FALSE(list()->item(0)->data(RegionPanel::kSoloRole).toBool());
    expectRowsMatchDocument();
    // The button says whether the selected region is the solo'd one.
    ASSERT_NO_FATAL_FAILURE(clickRow(list(), 0));
    EXPECT_FALSE(panel->soloButton()->isChecked());
    ASSERT_NO_FATAL_FAILURE(clickRow(list(), 1));
    EXPECT_TRUE(panel->soloButton()->isChecked());

    undo()->undo();
    EXPECT_EQ(document->soloRegion(), kNoSolo);
    EXPECT_FALSE(panel->soloButton()->isChecked());
    expectRowsMatchDocument();
    undo()->redo();
    EXPECT_EQ(document->soloRegion(), soloId);
    EXPECT_TRUE(panel->soloButton()->isChecked());
    expectRowsMatchDocument();

    // Clicking it again ends solo.
    ASSERT_NO_FATAL_FAILURE(click(panel->soloButton()));
    EXPECT_EQ(document->soloRegion(), kNoSolo);
    EXPECT_FALSE(panel->soloButton()->isChecked());
    expectRowsMatchDocument();
}

TEST_F(RegionPanelTest, RemoveTakesTheCurrentRegionButNeverTheLastOne)
{
    ASSERT_NO_FATAL_FAILURE(addUntil(2));
    const std::uint32_t kept = document->region(0).id;
    const std::uint32_t removed = document->region(1).id;
    ASSERT_NO_FATAL_FAILURE(click(panel->removeButton()));
    ASSERT_EQ(document->regionCount(), 1);
    EXPECT_EQ(document->region(0).id, kept);
    EXPECT_FALSE(panel->removeButton()->isEnabled());
    expectRowsMatchDocument();
    // A click on the disabled button does nothing.
    QTest::mouseClick(panel->removeButton(), Qt::LeftButton);
    EXPECT_EQ(document->regionCount(), 1);

    undo()->undo();
    ASSERT_EQ(document->regionCount(), 2);
    EXPECT_EQ(document->region(1).id, removed);
    EXPECT_TRUE(panel->removeButton()->isEnabled());
    expectRowsMatchDocument();
    undo()->redo();
    EXPECT_EQ(document->regionCount(), 1);
    EXPECT_FALSE(panel->removeButton()->isEnabled());
    expectRowsMatchDocument();
}

TEST_F(RegionPanelTest, ANewHeadStartsTheRowsOver)
{
    ASSERT_NO_FATAL_FAILURE(addUntil(3));
    TriangleMesh head = document->head();
    std::vector<float> weights(head.vertexCount(), 1.0f);
    document->replaceHead(std::move(head), std::move(weights), QStringLiteral("head.obj"));
    EXPECT_EQ(document->regionCount(), 1);
    expectRowsMatchDocument();
    undo()->undo();
    EXPECT_EQ(document->regionCount(), 3);
    expectRowsMatchDocument();
}

// --- Wisp panel ---------------------------------------------------------------------------------

class WispPanelTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        QStandardPaths::setTestModeEnabled(true);
        document = std::make_unique<Document>();
        // Two regions, the second current: edits must reach only it.
        document->addRegion(QStringLiteral("Fringe"));
        document->undoStack()->clear();
        ASSERT_EQ(document->currentRegion(), 1);
        panel = std::make_unique<WispPanel>(document.get());
        ASSERT_NO_FATAL_FAILURE(showActive(panel.get()));
    }
    ParameterPanel* parameters() const { return panel->parameterPanel(); }
    QUndoStack* undo() const { return document->undoStack(); }

    std::unique_ptr<Document> document;
    std::unique_ptr<WispPanel> panel; // destroyed before the document it watches
};

TEST_F(WispPanelTest, ShowsTheWispParametersOnlyInRegistryOrder)
{
    std::vector<Param> expected;
    for (const ParameterInfo& p : allParameters())
        if (p.group == ParamGroup::Wisp) {
            EXPECT_NE(parameters()->sliderFor(p.id), nullptr) << p.key;
            expected.push_back(p.id);
        }
    ASSERT_FALSE(expected.empty());
    EXPECT_EQ(parameters()->sliderFor(Param::Gravity), nullptr);
    EXPECT_EQ(parameters()->sliderFor(Param::Seed), nullptr);
    // Registry order: each row sits below the one before it.
    for (std::size_t i = 1; i < expected.size(); ++i)
        EXPECT_LT(parameters()->sliderFor(expected[i - 1])->mapTo(panel.get(), QPoint()).y(),
            parameters()->sliderFor(expected[i])->mapTo(panel.get(), QPoint()).y());
    EXPECT_EQ(panel->titleLabel()->text(), QStringLiteral("Fringe"));
    EXPECT_TRUE(panel->isEnabled());
}

TEST_F(WispPanelTest, TypingAValueEditsOnlyTheCurrentRegion)
{
    const double before = document->region(1).values.get(Param::ClumpDegree);
    const double other = document->region(0).values.get(Param::ClumpDegree);
    ASSERT_NO_FATAL_FAILURE(typeValue(parameters(), Param::ClumpDegree, QStringLiteral("-0.25")));
    EXPECT_DOUBLE_EQ(document->region(1).values.get(Param::ClumpDegree), -0.25);
    EXPECT_DOUBLE_EQ(document->region(0).values.get(Param::ClumpDegree), other);
    EXPECT_DOUBLE_EQ(document->parameters().get(Param::ClumpDegree), ParameterValues().get(Param::ClumpDegree));
    EXPECT_EQ(undo()->count(), 1);

    undo()->undo();
    EXPECT_DOUBLE_EQ(document->region(1).values.get(Param::ClumpDegree), before);
    EXPECT_NEAR(parameters()->value(Param::ClumpDegree), before, 1e-9);
    undo()->redo();
    EXPECT_DOUBLE_EQ(document->region(1).values.get(Param::ClumpDegree), -0.25);
    EXPECT_NEAR(parameters()->value(Param::ClumpDegree), -0.25, 1e-9);
}

TEST_F(WispPanelTest, SwitchingTheCurrentRegionShowsThatRegionsValues)
{
    document->editRegionParameter(0, Param::Length, 0.6, false);
    document->editRegionParameter(1, Param::Length, 0.1, false);
    EXPECT_NEAR(parameters()->value(Param::Length), 0.1, 1e-9);
    document->setCurrentRegion(0);
    EXPECT_NEAR(parameters()->value(Param::Length), 0.6, 1e-9);
    EXPECT_EQ(panel->titleLabel()->text(), QString::fromStdString(document->region(0).name));
    document->setCurrentRegion(1);
    EXPECT_NEAR(parameters()->value(Param::Length), 0.1, 1e-9);
    EXPECT_EQ(panel->titleLabel()->text(), QStringLiteral("Fringe"));
    // Showing a region's values is not an edit.
    EXPECT_EQ(undo()->count(), 2);
    // A rename elsewhere shows in the title.
    document->renameRegion(1, QStringLiteral("Bangs"));
    EXPECT_EQ(panel->titleLabel()->text(), QStringLiteral("Bangs"));
}

TEST_F(WispPanelTest, OneSliderDragIsOneUndoStep)
{
    QSlider* slider = parameters()->sliderFor(Param::ClumpDegree);
    ASSERT_NE(slider, nullptr);
    const double before = document->region(1).values.get(Param::ClumpDegree);
    ASSERT_NO_FATAL_FAILURE(dragSliderHandle(slider, 8, 4));
    const double after = document->region(1).values.get(Param::ClumpDegree);
    EXPECT_GT(after, before);
    EXPECT_DOUBLE_EQ(document->region(0).values.get(Param::ClumpDegree), before);
    EXPECT_EQ(undo()->count(), 1);
    undo()->undo();
    EXPECT_DOUBLE_EQ(document->region(1).values.get(Param::ClumpDegree), before);
    EXPECT_NEAR(parameters()->value(Param::ClumpDegree), before, 1e-9);
    undo()->redo();
    EXPECT_DOUBLE_EQ(document->region(1).values.get(Param::ClumpDegree), after);
}

TEST_F(WispPanelTest, ColourButtonsSetTheRegionsColoursThroughTheDialog)
{
    const glm::vec3 tipBefore = document->region(1).tipColour;
    const glm::vec3 rootBefore = document->region(1).rootColour;
    ASSERT_NO_FATAL_FAILURE(click(panel->rootColourButton()));
    auto* dialog = panel->findChild<QColorDialog*>();
    ASSERT_NE(dialog, nullptr) << "the root colour button opened no colour dialog";
    dialog->setCurrentColor(QColor(255, 0, 0));
    dialog->accept();
    EXPECT_EQ(document->region(1).rootColour, glm::vec3(1.0f, 0.0f, 0.0f));
    EXPECT_EQ(document->region(1).tipColour, tipBefore);
    EXPECT_EQ(document->region(0).rootColour, rootBefore);
    EXPECT_EQ(undo()->count(), 1);
    const QImage swatch = panel->rootColourButton()->icon().pixmap(panel->rootColourButton()->iconSize()).toImage();
    EXPECT_EQ(swatch.pixelColor(swatch.width() / 2, swatch.height() / 2), QColor(255, 0, 0));
    QTest::qWait(0); // lets the closed dialog delete itself

    // Cancelling changes nothing.
    ASSERT_NO_FATAL_FAILURE(click(panel->tipColourButton()));
    dialog = panel->findChild<QColorDialog*>();
    ASSERT_NE(dialog, nullptr);
    dialog->setCurrentColor(QColor(0, 0, 255));
    dialog->reject();
    EXPECT_EQ(document->region(1).tipColour, tipBefore);
    EXPECT_EQ(undo()->count(), 1);

    undo()->undo();
    EXPECT_EQ(document->region(1).rootColour, rootBefore);
    const QImage undone = panel->rootColourButton()->icon().pixmap(panel->rootColourButton()->iconSize()).toImage();
    EXPECT_NE(undone.pixelColor(undone.width() / 2, undone.height() / 2), QColor(255, 0, 0));
}

TEST_F(WispPanelTest, FollowsUndoOfTheRegionStructure)
{
    // Undoing the region's removal brings its values back into view.
    document->editRegionParameter(1, Param::CurlTurns, 30.0, false);
    document->removeRegion(1);
    EXPECT_NE(panel->titleLabel()->text(), QStringLiteral("Fringe"));
    undo()->undo();
    document->setCurrentRegion(1);
    EXPECT_EQ(panel->titleLabel()->text(), QStringLiteral("Fringe"));
    EXPECT_NEAR(parameters()->value(Param::CurlTurns), 30.0, 1e-9);
}

} // namespace
