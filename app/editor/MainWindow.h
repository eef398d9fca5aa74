#pragma once
// The editor's window. It only wires things together: the document, the simulation host, the
// viewport, the panels and the actions are classes of their own.
//
// Thread: GUI.

#include "app/editor/ShortcutsDialog.h"

#include <QMainWindow>
#include <QPointer>

class QAction;
class QDockWidget;
class QUndoView;

namespace wisp {

class BrushPanel;
class Document;
class FileMenu;
class HeadMoveTool;
class MotionPanel;
class PaintTool;
class ParameterPanel;
class PresetBrowser;
class RegionPanel;
class ShortcutsDialog;
class WispPanel;
class SimulationHost;
class StylePanel;
class StyleTool;
class TimelineDock;
class Viewport;

class MainWindow : public QMainWindow {
    Q_OBJECT
public:
    explicit MainWindow(QWidget* parent = nullptr);
    ~MainWindow() override;

    Document* document() const { return m_document; }
    SimulationHost* simulation() const { return m_simulation; }
    Viewport* viewport() const { return m_viewport; }
    ParameterPanel* forcePanel() const { return m_forcePanel; }
    ParameterPanel* groomPanel() const { return m_groomPanel; }
    QAction* playAction() const { return m_play; }
    QAction* stepAction() const { return m_step; }
    QAction* resetAction() const { return m_reset; }
    QAction* resetHeadAction() const { return m_resetHead; } // Ctrl+Shift+H
    HeadMoveTool* headTool() const { return m_headTool; }
    MotionPanel* motionPanel() const { return m_motionPanel; }
    QAction* paintAction() const { return m_paintAction; }
    QAction* overlayAction() const { return m_overlayAction; }
    QAction* leaveToolAction() const { return m_leaveToolAction; } // Esc
    QAction* shortcutsAction() const { return m_shortcutsAction; } // Help ▸ Keyboard Shortcuts
    ShortcutsDialog* shortcutsDialog() const { return m_shortcutsDialog; } // null until opened
    PaintTool* paintTool() const { return m_paintTool; }
    StyleTool* styleTool() const { return m_styleTool; }
    StylePanel* stylePanel() const { return m_stylePanel; }
    RegionPanel* regionPanel() const { return m_regionPanel; }
    WispPanel* wispPanel() const { return m_wispPanel; }
    BrushPanel* brushPanel() const { return m_brushPanel; }
    PresetBrowser* presetBrowser() const { return m_presetBrowser; }
    QMenu* displayDensityMenu() const { return m_densityMenu; }
    TimelineDock* timelineDock() const { return m_timeline; }

    FileMenu* fileMenu() const { return m_fileMenu; }

protected:
    void closeEvent(QCloseEvent* event) override;
    void showEvent(QShowEvent* event) override;

private:
    void createActions();
    void createDocks();
    void connectSimulation();
    void restoreSettings();
    void saveSettings() const;
    void updatePlayAction(bool playing);
    void showGrowthOverlay(); // the current region's weights on the head
    void showGrowthTint(); // whether the viewport shows them
    void showBody();
    void updateTitle(); // the project's name, and * while it has unsaved changes
    QDockWidget* addPanelDock(const QString& title, const QString& objectName, QWidget* panel, Qt::DockWidgetArea area);

    Document* m_document = nullptr;
    SimulationHost* m_simulation = nullptr;
    Viewport* m_viewport = nullptr;
    ParameterPanel* m_forcePanel = nullptr;
    ParameterPanel* m_groomPanel = nullptr;
    QUndoView* m_history = nullptr;
    PaintTool* m_paintTool = nullptr;
    StyleTool* m_styleTool = nullptr;
    StylePanel* m_stylePanel = nullptr;
    RegionPanel* m_regionPanel = nullptr;
    WispPanel* m_wispPanel = nullptr;
    BrushPanel* m_brushPanel = nullptr;
    PresetBrowser* m_presetBrowser = nullptr;
    TimelineDock* m_timeline = nullptr;
    QAction* m_paintAction = nullptr;
    QAction* m_overlayAction = nullptr;
    QAction* m_leaveToolAction = nullptr;
    QAction* m_shortcutsAction = nullptr;
    QPointer<ShortcutsDialog> m_shortcutsDialog;
    QAction* m_play = nullptr;
    QAction* m_step = nullptr;
    QAction* m_reset = nullptr;
    QAction* m_resetHead = nullptr;
    HeadMoveTool* m_headTool = nullptr;
    MotionPanel* m_motionPanel = nullptr;
    QMenu* m_viewMenu = nullptr;
    QMenu* m_densityMenu = nullptr; // View ▸ Display Density
    QMenu* m_editMenu = nullptr;
    FileMenu* m_fileMenu = nullptr;
    bool m_recoveryOffered = false;
};

} // namespace wisp
