#include "app/editor/ShortcutsDialog.h"

#include <QAction>
#include <QDialogButtonBox>
#include <QHeaderView>
#include <QMainWindow>
#include <QMenu>
#include <QMenuBar>
#include <QTableWidget>
#include <QVBoxLayout>

#include <set>

namespace wisp {

namespace {

QString plain(QString text)
{
    // "&Undo", "Save &As…": the mnemonic marker is not part of the name ("&&" is a real ampersand).
    text.replace(QStringLiteral("&&"), QStringLiteral("\x01"));
    text.remove(QLatin1Char('&'));
    text.replace(QStringLiteral("\x01"), QStringLiteral("&"));
    return text;
}

QString keysOf(const QAction* action)
{
    QStringList keys;
    for (const QKeySequence& key : action->shortcuts())
        keys << key.toString(QKeySequence::NativeText);
    return keys.join(QStringLiteral(", "));
}

void collectMenu(
    const QMenu* menu, const QString& path, std::vector<ShortcutEntry>& out, std::set<const QAction*>& seen)
{
    for (const QAction* action : menu->actions()) {
        if (action->menu()) {
            collectMenu(action->menu(), path + QStringLiteral(" ▸ ") + plain(action->menu()->title()), out, seen);
            continue;
        }
        if (action->isSeparator() || action->shortcuts().isEmpty() || !seen.insert(action).second)
            continue;
        out.push_back({ keysOf(action), plain(action->text()), path });
    }
}

// What the viewport, the brushes and the sliders do with the mouse and modifiers (no actions).
const std::vector<ShortcutEntry>& mouseBindings()
{
    static const std::vector<ShortcutEntry> bindings{
        { QObject::tr("Alt+Left drag, Middle drag"), QObject::tr("Orbit the camera"), QObject::tr("Viewport") },
        { QObject::tr("Shift+Middle drag"), QObject::tr("Pan the camera"), QObject::tr("Viewport") },
        { QObject::tr("Wheel"), QObject::tr("Zoom"), QObject::tr("Viewport") },
        { QObject::tr("Left drag"), QObject::tr("Paint, or use the styling tool"), QObject::tr("Viewport") },
        { QObject::tr("Ctrl+Left drag"), QObject::tr("Erase (paint); shrink, take out, towel-dry, wash out (styling)"),
            QObject::tr("Viewport") },
        { QObject::tr("Shift+Left drag"), QObject::tr("Smooth the growth weights (paint)"), QObject::tr("Viewport") },
        { QObject::tr("[ and ]"), QObject::tr("Brush radius smaller / larger"), QObject::tr("Viewport") },
        { QObject::tr("Shift+drag"), QObject::tr("Fine: a tenth as fast"), QObject::tr("Sliders") },
        { QObject::tr("Ctrl+drag"), QObject::tr("Snap to round values"), QObject::tr("Sliders") },
    };
    return bindings;
}

} // namespace

std::vector<ShortcutEntry> shortcutEntries(const QWidget* window)
{
    std::vector<ShortcutEntry> out;
    std::set<const QAction*> seen;
    if (const auto* main = qobject_cast<const QMainWindow*>(window); main && main->menuBar())
        for (const QAction* top : main->menuBar()->actions())
            if (top->menu())
                collectMenu(top->menu(), plain(top->menu()->title()), out, seen);
    // Actions that are in no menu (a panel's buttons): named by the widget that holds them.
    for (const QAction* action : window->findChildren<QAction*>()) {
        if (action->shortcuts().isEmpty() || !seen.insert(action).second)
            continue;
        const QWidget* holder = action->associatedObjects().isEmpty()
            ? nullptr
            : qobject_cast<const QWidget*>(action->associatedObjects().front());
        out.push_back({ keysOf(action), plain(action->text()),
            holder ? holder->windowTitle().isEmpty() ? holder->objectName() : holder->windowTitle() : QString() });
    }
    const auto& mouse = mouseBindings();
    out.insert(out.end(), mouse.begin(), mouse.end());
    return out;
}

ShortcutsDialog::ShortcutsDialog(QWidget* window)
    : QDialog(window)
{
    setWindowTitle(tr("Keyboard Shortcuts"));
    setObjectName(QStringLiteral("shortcutsDialog"));
    auto* layout = new QVBoxLayout(this);
    const std::vector<ShortcutEntry> entries = shortcutEntries(window);
    m_table = new QTableWidget(static_cast<int>(entries.size()), 3, this);
    m_table->setHorizontalHeaderLabels({ tr("Keys"), tr("Does"), tr("Where") });
    m_table->verticalHeader()->hide();
    m_table->setEditTriggers(QAbstractItemView::NoEditTriggers);
    m_table->setSelectionBehavior(QAbstractItemView::SelectRows);
    for (int row = 0; row < static_cast<int>(entries.size()); ++row) {
        const ShortcutEntry& e = entries[static_cast<std::size_t>(row)];
        m_table->setItem(row, 0, new QTableWidgetItem(e.keys));
        m_table->setItem(row, 1, new QTableWidgetItem(e.action));
        m_table->setItem(row, 2, new QTableWidgetItem(e.where));
    }
    m_table->resizeColumnsToContents();
    m_table->horizontalHeader()->setStretchLastSection(true);
    layout->addWidget(m_table);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Close, this);
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
    layout->addWidget(buttons);
    resize(620, 560);
}

} // namespace wisp
