#pragma once
// The region panel: the document's growth regions, one row each in order, with their visibility
// and solo state, and buttons to add, remove, reorder and solo them. Selecting a row makes that
// region the current one (what the wisp panel edits and the brush paints).
//
// Every change goes to the Document as an undoable edit; the rows are only ever rebuilt from the
// document (after an edit, undo, redo or a new head), never edited ahead of it.
//
// Thread: GUI.

#include <QWidget>

#include <cstdint>

class QListWidget;
class QListWidgetItem;
class QToolButton;

namespace wisp {

class Document;

class RegionPanel : public QWidget {
    Q_OBJECT
public:
    explicit RegionPanel(Document* document, QWidget* parent = nullptr);

    // Item data the rows carry besides their name and check state (for tests and delegates).
    static constexpr int kRegionIdRole = Qt::UserRole; // std::uint32_t GrowthRegion::id
    static constexpr int kSoloRole = Qt::UserRole + 1; // bool: this region is solo'd

    QListWidget* listWidget() const { return m_list; }
    QToolButton* addButton() const { return m_add; }
    QToolButton* removeButton() const { return m_remove; }
    QToolButton* upButton() const { return m_up; }
    QToolButton* downButton() const { return m_down; }
    QToolButton* soloButton() const { return m_solo; }

private:
    void createButtons();
    void connectDocument();

    // Document → rows: makes the rows, their names, check states and solo marks, the selected row
    // and the buttons match the document, emitting nothing back to it.
    void refresh();
    void showRegion(int row);
    void showCurrent();
    void updateButtons();
    int validCurrent() const; // the document's current region, or -1 while it has none

    // Rows → document.
    void itemEdited(QListWidgetItem* item);
    void addRegion();
    void removeCurrent();
    void moveCurrent(int offset);
    void soloToggled(bool on);
    QString unusedRegionName() const;

    Document* m_document;
    QListWidget* m_list = nullptr;
    QToolButton* m_add = nullptr;
    QToolButton* m_remove = nullptr;
    QToolButton* m_up = nullptr;
    QToolButton* m_down = nullptr;
    QToolButton* m_solo = nullptr;
    // True while the panel shows the document: the item and button signals this causes are the
    // document's own state coming back, not the artist's edits, and must not be pushed again.
    bool m_showing = false;
};

} // namespace wisp
