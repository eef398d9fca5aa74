#pragma once
// Help ▸ Keyboard Shortcuts: every key binding of the window, read from its actions when the dialog
// opens (so the list cannot go stale), then the mouse and modifier bindings of the viewport, the
// brushes and the sliders, which are not actions.
//
// Thread: GUI.

#include <QDialog>
#include <QString>

#include <vector>

class QTableWidget;

namespace wisp {

struct ShortcutEntry {
    QString keys; // "Ctrl+Shift+S", native text; several keys joined by ", "
    QString action; // "Save As…", without the mnemonic's &
    QString where; // the menu path ("File"), or the toolbar or panel that holds the action
};

// Every action inside `window` that has a shortcut (one entry each, in menu order first), then the
// bindings that are not actions.
std::vector<ShortcutEntry> shortcutEntries(const QWidget* window);

class ShortcutsDialog : public QDialog {
    Q_OBJECT
public:
    explicit ShortcutsDialog(QWidget* window);
    QTableWidget* table() const { return m_table; }

private:
    QTableWidget* m_table = nullptr;
};

} // namespace wisp
