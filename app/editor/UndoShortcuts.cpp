#include "app/editor/UndoShortcuts.h"

#include <QAbstractSpinBox>
#include <QApplication>
#include <QDoubleSpinBox>
#include <QKeyEvent>
#include <QLineEdit>
#include <QSpinBox>

namespace wisp {

namespace {

// The spin box `watched` belongs to (itself, or the spin box its line edit is in), or null.
QAbstractSpinBox* spinBoxOf(QObject* watched)
{
    if (auto* box = qobject_cast<QAbstractSpinBox*>(watched))
        return box;
    if (auto* edit = qobject_cast<QLineEdit*>(watched))
        return qobject_cast<QAbstractSpinBox*>(edit->parent());
    return nullptr;
}

// Whether the box shows text the artist typed and has not committed: its text is not what its
// value reads as (a committed value is shown reformatted: "3" becomes "3.00 m/s²").
bool hasOwnEdit(QAbstractSpinBox* box)
{
    auto* edit = box->findChild<QLineEdit*>();
    if (!edit)
        return false;
    QString committed;
    if (auto* real = qobject_cast<QDoubleSpinBox*>(box))
        committed = real->prefix() + real->textFromValue(real->value()) + real->suffix();
    else if (auto* whole = qobject_cast<QSpinBox*>(box))
        committed = whole->prefix() + whole->locale().toString(whole->value()) + whole->suffix();
    else
        return true; // another kind of spin box: its keys stay its own
    return edit->text() != committed;
}

} // namespace

UndoShortcuts::UndoShortcuts(QWidget* window)
    : QObject(window)
    , m_window(window)
{
    qApp->installEventFilter(this);
}

bool UndoShortcuts::eventFilter(QObject* watched, QEvent* event)
{
    if (event->type() != QEvent::ShortcutOverride)
        return false;
    auto* key = static_cast<QKeyEvent*>(event);
    if (!key->matches(QKeySequence::Undo) && !key->matches(QKeySequence::Redo))
        return false;
    QAbstractSpinBox* box = spinBoxOf(watched);
    if (!box || box->window() != m_window || hasOwnEdit(box))
        return false;
    // Not overridden: the key goes on to the window's shortcuts (Edit ▸ Undo / Redo).
    event->ignore();
    return true;
}

} // namespace wisp
