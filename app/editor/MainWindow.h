#pragma once
// The editor's window. It only wires things together: the document, the simulation host, the
// viewport, the panels and the actions are classes of their own.
//
// Thread: GUI.

#include <QMainWindow>

class QAction;
class QDockWidget;
class QUndoView;

namespace wisp {

class Document;
class ParameterPanel;
class SimulationHost;
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

    // Loads a head mesh file (OBJ, PLY, OFF, STL) as an undoable edit; reports problems in a dialog.
    bool openHead(const QString& path);

protected:
    void closeEvent(QCloseEvent* event) override;

private:
    void createActions();
    void createDocks();
    void connectSimulation();
    void restoreSettings();
    void saveSettings() const;
    void updatePlayAction(bool playing);
    QDockWidget* addPanelDock(const QString& title, const QString& objectName, QWidget* panel, Qt::DockWidgetArea area);

    Document* m_document = nullptr;
    SimulationHost* m_simulation = nullptr;
    Viewport* m_viewport = nullptr;
    ParameterPanel* m_forcePanel = nullptr;
    ParameterPanel* m_groomPanel = nullptr;
    QUndoView* m_history = nullptr;
    QAction* m_play = nullptr;
    QAction* m_step = nullptr;
    QAction* m_reset = nullptr;
    QMenu* m_viewMenu = nullptr;
};

}  // namespace wisp
