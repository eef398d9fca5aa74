#pragma once
// Ctrl+Z and Ctrl+Shift+Z (the platform's Undo and Redo keys) reach the document's undo stack even
// while a spin box has the keyboard focus, which it has right after a value was typed into it. A
// line edit claims those keys for its own undo (a ShortcutOverride), so the window's Undo action
// would never fire; this filter lets the spin box keep them only while it holds an edit of its own
// (text typed and not yet committed with Enter or by leaving it). Other line edits (a region's
// name being typed) keep their keys.
//
// Thread: GUI.

#include <QObject>

class QWidget;

namespace wisp {

class UndoShortcuts : public QObject {
    Q_OBJECT
public:
    // Filters the application's events for the widgets inside `window`.
    explicit UndoShortcuts(QWidget* window);

protected:
    bool eventFilter(QObject* watched, QEvent* event) override;

private:
    QWidget* m_window;
};

} // namespace wisp
