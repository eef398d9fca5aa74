#include "app/editor/MainWindow.h"

#include "sim/geometry/Body.h"

#include "app/editor/AboutText.h"
#include "app/editor/BakeController.h"
#include "app/editor/BrushPanel.h"
#include "app/editor/Document.h"
#include "app/editor/FileMenu.h"
#include "app/editor/HeadMoveTool.h"
#include "app/editor/MotionPanel.h"
#include "app/editor/PaintTool.h"
#include "app/editor/PresetBrowser.h"
#include "app/editor/ProjectController.h"
#include "app/editor/RegionPanel.h"
#include "app/editor/ShortcutsDialog.h"
#include "app/editor/SimulationHost.h"
#include "app/editor/StylePanel.h"
#include "app/editor/StyleTool.h"
#include "app/editor/TimelineDock.h"
#include "app/editor/UndoShortcuts.h"
#include "app/editor/WispPanel.h"
#include "io/MeshReader.h"
#include "sim/groom/GrowthMap.h"
#include "widgets/ParameterPanel.h"
#include "widgets/Viewport.h"

#include <QAction>
#include <QActionGroup>
#include <QApplication>
#include <QCheckBox>
#include <QCloseEvent>
#include <QDockWidget>
#include <QFileDialog>
#include <QFileInfo>
#include <QMenu>
#include <QMenuBar>
#include <QMessageBox>
#include <QScrollArea>
#include <QSettings>
#include <QStatusBar>
#include <QTimer>
#include <QToolBar>
#include <QUndoStack>
#include <QUndoView>

namespace wisp {

namespace {

std::vector<Param> parametersIn(ParamGroup group)
{
    std::vector<Param> ids;
    for (const ParameterInfo& p : allParameters())
        if (p.group == group)
            ids.push_back(p.id);
    return ids;
}

// The force panel: what an artist drags while the hair moves (issue: gravity, wind, turbulence,
// drag, damping, stiffness, substeps), in that order, with what the hair collides with.
std::vector<Param> forceParameters()
{
    return { Param::Gravity, Param::WindSpeed, Param::WindAzimuth, Param::WindElevation, Param::Turbulence, Param::Drag,
        Param::Damping, Param::DryingTime, Param::Stiffness, Param::GlobalShape, Param::Friction, Param::Volume,
        Param::HairFriction, Param::Body, Param::Substeps, Param::TimeStep, Param::SimulateAllStrands };
}

} // namespace

MainWindow::MainWindow(QWidget* parent)
    : QMainWindow(parent)
{
    setWindowTitle(QStringLiteral("Wisp"));
    m_document = new Document(this);
    m_simulation = new SimulationHost(this);
    m_viewport = new Viewport(this);
    m_viewport->setHead(m_document->head());
    showBody();
    setCentralWidget(m_viewport);
    m_paintTool = new PaintTool(m_document, m_viewport, this);
    m_styleTool = new StyleTool(m_document, m_viewport, m_simulation, m_paintTool, this);
    m_stylePanel = new StylePanel(m_styleTool);
    m_headTool = new HeadMoveTool(m_document, m_viewport, m_simulation, this);

    createActions();
    createDocks();
    connectSimulation();
    restoreSettings();
    statusBar()->showMessage(tr("Space plays or pauses · Alt+drag or middle-drag orbits · Shift+middle-drag pans · "
                                "wheel zooms · Ctrl+Alt+drag turns the head · F frames the head · B paints where hair "
                                "grows · C X G P W S D style the hair"));
    showGrowthOverlay();
    m_simulation->setScene(
        m_document->headModel(), m_document->regions(), m_document->soloRegion(), m_document->parameters());
    m_simulation->play();
}

MainWindow::~MainWindow()
{
    // The children go after this body: the document's undo stack, clearing, must not call back
    // into a window that is half gone.
    m_document->undoStack()->disconnect(this);
    m_document->undoStack()->disconnect(m_fileMenu->projects()); // it watches the stack for autosave
    m_document->disconnect(this);
    m_fileMenu->projects()->disconnect(this);
}

void MainWindow::createActions()
{
    m_fileMenu = new FileMenu(this, m_document, m_simulation, m_viewport);
    connect(
        m_fileMenu, &FileMenu::message, this, [this](const QString& text) { statusBar()->showMessage(text, 8000); });
    connect(m_fileMenu->projects(), &ProjectController::currentPathChanged, this, &MainWindow::updateTitle);
    connect(m_document->undoStack(), &QUndoStack::cleanChanged, this, [this] { updateTitle(); });
    updateTitle();

    QMenu* edit = menuBar()->addMenu(tr("&Edit"));
    m_editMenu = edit;
    QAction* undo = m_document->undoStack()->createUndoAction(this, tr("&Undo"));
    undo->setShortcut(QKeySequence::Undo);
    QAction* redo = m_document->undoStack()->createRedoAction(this, tr("&Redo"));
    redo->setShortcut(QKeySequence::Redo);
    edit->addAction(undo);
    edit->addAction(redo);
    new UndoShortcuts(this); // and from a spin box that has focus, unless it holds an edit of its own

    m_viewMenu = menuBar()->addMenu(tr("&View"));
    QAction* frame = m_viewMenu->addAction(tr("&Frame Head"), m_viewport, &Viewport::frameHead);
    frame->setShortcut(QKeySequence(Qt::Key_F));
    QAction* grid = m_viewMenu->addAction(tr("Show &Grid"));
    grid->setCheckable(true);
    grid->setChecked(m_viewport->showGrid());
    connect(grid, &QAction::toggled, m_viewport, &Viewport::setShowGrid);
    // Drawn strands per simulated one (render-time children); saved in the project.
    m_densityMenu = m_viewMenu->addMenu(tr("Display &Density"));
    m_densityMenu->setToolTipsVisible(true);
    auto* densities = new QActionGroup(m_densityMenu);
    for (const float density : { 0.25f, 0.5f, 1.0f, 2.0f, 4.0f }) {
        QAction* action = m_densityMenu->addAction(QStringLiteral("%1×").arg(static_cast<double>(density)));
        action->setCheckable(true);
        action->setData(static_cast<double>(density));
        action->setToolTip(density > 1.0f
                ? tr("Draw %1 strands for every simulated strand, interpolated between neighbours")
                      .arg(static_cast<double>(density))
                : tr("Draw an even share of the strands, widened to keep the coverage"));
        densities->addAction(action);
        connect(action, &QAction::triggered, this, [this, density] { m_viewport->setDisplayDensity(density); });
    }
    const auto showDensity = [this] { // a project may have brought another density
        for (QAction* action : m_densityMenu->actions())
            action->setChecked(action->data().toFloat() == m_viewport->displayDensity());
    };
    connect(m_densityMenu, &QMenu::aboutToShow, this, showDensity);
    showDensity();
    QAction* shadows = m_viewMenu->addAction(tr("Show &Shadows"));
    shadows->setObjectName(QStringLiteral("showShadowsAction"));
    shadows->setCheckable(true);
    shadows->setChecked(m_viewport->shadowsEnabled());
    shadows->setToolTip(tr("Hair shades hair and the head, and the head shades the hair"));
    connect(shadows, &QAction::toggled, m_viewport, &Viewport::setShadowsEnabled);
    QAction* followLight = m_viewMenu->addAction(tr("Light &Follows Camera"));
    followLight->setObjectName(QStringLiteral("lightFollowsCameraAction"));
    followLight->setCheckable(true);
    followLight->setChecked(m_viewport->lightFollowsCamera());
    followLight->setToolTip(tr("Off: the key light is fixed to the head, so orbiting shows its lit and shaded sides"));
    connect(followLight, &QAction::toggled, m_viewport, &Viewport::setLightFollowsCamera);
    m_viewMenu->addSeparator();

    QMenu* toolsMenu = menuBar()->addMenu(tr("&Tools"));
    m_paintAction = toolsMenu->addAction(tr("&Paint Growth"));
    m_paintAction->setCheckable(true);
    m_paintAction->setShortcut(QKeySequence(Qt::Key_B));
    m_paintAction->setToolTip(tr("Paint where the current region's hair grows (B)"));
    connect(m_paintAction, &QAction::toggled, m_paintTool, &PaintTool::setActive);
    connect(m_paintTool, &PaintTool::activeChanged, m_paintAction, &QAction::setChecked);
    // One tool at a time: painting growth or one of the salon brushes (or none: the camera only).
    auto* toolGroup = new QActionGroup(this);
    toolGroup->setExclusionPolicy(QActionGroup::ExclusionPolicy::ExclusiveOptional);
    toolGroup->addAction(m_paintAction);
    toolsMenu->addSeparator();
    for (const auto& [brush, action] : m_stylePanel->brushActions()) {
        toolGroup->addAction(action);
        toolsMenu->addAction(action);
    }
    toolsMenu->addSeparator();
    m_leaveToolAction = toolsMenu->addAction(tr("&Leave Tool"));
    m_leaveToolAction->setShortcut(QKeySequence(Qt::Key_Escape));
    m_leaveToolAction->setToolTip(tr("Put the paint or styling tool down: the mouse moves the camera only (Esc)"));
    connect(m_leaveToolAction, &QAction::triggered, this, [this] {
        m_paintTool->setActive(false);
        m_styleTool->setBrush(std::nullopt);
        m_timeline->leaveCache(); // and the baked cache: back to the live simulation
    });
    m_overlayAction = m_viewMenu->addAction(tr("Show Growth &Weights"));
    m_overlayAction->setCheckable(true);
    // Off at first: the tint is a painting aid; the head shows the hair's root colour instead.
    m_overlayAction->setChecked(false);
    m_overlayAction->setShortcut(QKeySequence(tr("Shift+W")));
    connect(m_overlayAction, &QAction::toggled, this, &MainWindow::showGrowthTint);
    connect(m_paintTool, &PaintTool::activeChanged, this, &MainWindow::showGrowthTint);

    QMenu* sim = menuBar()->addMenu(tr("&Simulation"));
    m_play = sim->addAction(tr("&Play"));
    m_play->setCheckable(true);
    m_play->setShortcut(QKeySequence(Qt::Key_Space));
    m_play->setShortcutContext(Qt::WindowShortcut);
    connect(m_play, &QAction::triggered, this, [this](bool on) {
        if (on)
            m_timeline->leaveCache(); // Play is the live simulation's: the cache gives the viewport back
        on ? m_simulation->play() : m_simulation->pause();
    });
    m_step = sim->addAction(tr("&Step"), m_simulation, &SimulationHost::stepOnce);
    m_step->setShortcut(QKeySequence(Qt::Key_Period));
    m_step->setToolTip(tr("Advance one time step while paused (.)"));
    m_reset = sim->addAction(tr("&Reset to Rest"), m_simulation, &SimulationHost::resetToRest);
    m_reset->setShortcut(QKeySequence(tr("Ctrl+R")));
    sim->addSeparator();
    m_resetHead = sim->addAction(tr("Reset &Head Motion"), this, [this] {
        if (!(m_document->headMotion() == HeadMotion{}))
            m_document->setHeadMotion(HeadMotion{}, tr("Reset Head Motion"));
    });
    m_resetHead->setShortcut(QKeySequence(tr("Ctrl+Shift+H")));
    m_resetHead->setToolTip(tr("The head back at rest: no keys, no procedural motion (Ctrl+Shift+H)"));
    updatePlayAction(false);

    QMenu* help = menuBar()->addMenu(tr("&Help"));
    m_shortcutsAction = help->addAction(tr("&Keyboard Shortcuts"), this, [this] {
        // Not modal: it can stay open beside the work. Built anew each time, from the actions.
        if (m_shortcutsDialog)
            m_shortcutsDialog->deleteLater();
        m_shortcutsDialog = new ShortcutsDialog(this);
        m_shortcutsDialog->setAttribute(Qt::WA_DeleteOnClose);
        m_shortcutsDialog->show();
    });
    help->addAction(tr("&About Wisp"), this,
        [this] { QMessageBox::about(this, tr("About Wisp"), aboutText(m_viewport->glDescription())); });

    QToolBar* tools = addToolBar(tr("Simulation"));
    tools->setObjectName(QStringLiteral("simulationToolBar"));
    tools->addAction(m_play);
    tools->addAction(m_step);
    tools->addAction(m_reset);
    tools->addSeparator();
    tools->addAction(frame);
    tools->addAction(m_paintAction);
    // Named as toolbars: the Styling panel's entry is "Styling" too.
    tools->toggleViewAction()->setText(tr("Simulation Toolbar"));
    m_viewMenu->addAction(tools->toggleViewAction());
    QToolBar* styling = addToolBar(tr("Styling"));
    styling->setObjectName(QStringLiteral("stylingToolBar"));
    for (const auto& [brush, action] : m_stylePanel->brushActions())
        styling->addAction(action);
    styling->toggleViewAction()->setText(tr("Styling Toolbar"));
    m_viewMenu->addAction(styling->toggleViewAction());
}

QDockWidget* MainWindow::addPanelDock(
    const QString& title, const QString& objectName, QWidget* panel, Qt::DockWidgetArea area)
{
    auto* dock = new QDockWidget(title, this);
    dock->setObjectName(objectName);
    auto* scroll = new QScrollArea(dock);
    scroll->setWidgetResizable(true);
    scroll->setWidget(panel);
    dock->setWidget(scroll);
    addDockWidget(area, dock);
    m_viewMenu->addAction(dock->toggleViewAction());
    return dock;
}

void MainWindow::createDocks()
{
    m_forcePanel = new ParameterPanel(forceParameters());
    m_groomPanel = new ParameterPanel(parametersIn(ParamGroup::Groom));
    m_regionPanel = new RegionPanel(m_document);
    m_wispPanel = new WispPanel(m_document);
    m_brushPanel = new BrushPanel(m_paintTool);
    m_presetBrowser = new PresetBrowser(m_document);
    m_timeline = new TimelineDock(m_document);
    m_motionPanel = new MotionPanel(m_document, m_headTool);
    QDockWidget* forces
        = addPanelDock(tr("Forces"), QStringLiteral("forcesDock"), m_forcePanel, Qt::RightDockWidgetArea);
    QDockWidget* groom = addPanelDock(tr("Groom"), QStringLiteral("groomDock"), m_groomPanel, Qt::RightDockWidgetArea);
    tabifyDockWidget(forces, groom);
    forces->raise();
    QDockWidget* regions
        = addPanelDock(tr("Regions"), QStringLiteral("regionsDock"), m_regionPanel, Qt::LeftDockWidgetArea);
    QDockWidget* wisp = addPanelDock(tr("Wisp"), QStringLiteral("wispDock"), m_wispPanel, Qt::LeftDockWidgetArea);
    QDockWidget* brush = addPanelDock(tr("Brush"), QStringLiteral("brushDock"), m_brushPanel, Qt::LeftDockWidgetArea);
    QDockWidget* styling
        = addPanelDock(tr("Styling"), QStringLiteral("stylingDock"), m_stylePanel, Qt::LeftDockWidgetArea);
    QDockWidget* presets
        = addPanelDock(tr("Presets"), QStringLiteral("presetsDock"), m_presetBrowser, Qt::RightDockWidgetArea);
    tabifyDockWidget(groom, presets);
    QDockWidget* motion
        = addPanelDock(tr("Motion"), QStringLiteral("motionDock"), m_motionPanel, Qt::RightDockWidgetArea);
    tabifyDockWidget(presets, motion);
    const auto showFor8s = [this](const QString& text) { statusBar()->showMessage(text, 8000); };
    connect(m_motionPanel, &MotionPanel::message, this, showFor8s);
    // One current time, as in Blender: the timeline's frame is where keys go, and a selected key
    // takes the timeline to it.
    m_headTool->setTimelineSeconds([this] { return m_timeline->frameSeconds(); });
    connect(m_motionPanel, &MotionPanel::keySelected, m_timeline, &TimelineDock::goToSeconds);
    connect(m_headTool, &HeadMoveTool::message, this, showFor8s);
    forces->raise();
    connect(m_presetBrowser, &PresetBrowser::message, this,
        [this](const QString& text) { statusBar()->showMessage(text, 8000); });
    splitDockWidget(regions, wisp, Qt::Vertical);
    tabifyDockWidget(wisp, brush);
    tabifyDockWidget(brush, styling);
    wisp->raise();
    connect(m_styleTool, &StyleTool::message, this, [this](const QString& text) {
        if (text.isEmpty())
            statusBar()->clearMessage(); // a new stroke: the last one's news is old
        else
            statusBar()->showMessage(text, 5000);
    });
    // A styling tool picked: its panel and the brush settings it shares come forward.
    connect(m_styleTool, &StyleTool::brushChanged, this, [this, styling](std::optional<StyleBrush> b) {
        if (b)
            styling->raise();
        showGrowthTint();
    });
    connect(m_brushPanel, &BrushPanel::showOverlayToggled, m_overlayAction, &QAction::setChecked);
    connect(m_overlayAction, &QAction::toggled, m_brushPanel->overlayBox(), &QCheckBox::setChecked);

    addPanelDock(tr("Timeline"), QStringLiteral("timelineDock"), m_timeline, Qt::BottomDockWidgetArea);
    // File ▸ Export Bake, after Export Hair (which writes the one frame shown).
    QAction* exportBake = new QAction(tr("Export &Bake…"), this);
    exportBake->setToolTip(tr("Write the timeline's bake as .usda or a .hair sequence"));
    connect(exportBake, &QAction::triggered, m_timeline, &TimelineDock::chooseExport);
    connect(m_timeline->bake(), &BakeController::finished, this, [exportBake] { exportBake->setEnabled(true); });
    exportBake->setEnabled(false);
    const QList<QAction*> fileActions = m_fileMenu->menu()->actions();
    for (qsizetype i = 0; i < fileActions.size(); ++i)
        if (fileActions[i]->text() == tr("&Export Hair…")) {
            m_fileMenu->menu()->insertAction(fileActions.value(i + 1), exportBake); // null: at the end
            break;
        }
    connect(m_timeline, &TimelineDock::message, this,
        [this](const QString& text) { statusBar()->showMessage(text, 8000); });
    // A bake and the live simulation would share the cores: the live one pauses (Play resumes it).
    connect(m_timeline, &TimelineDock::bakeStarted, m_simulation, &SimulationHost::pause);
    // The cache shown: exactly its frame, with the live simulation paused under it.
    connect(m_timeline, &TimelineDock::cacheFrameShown, this, [this](const FramePtr& frame) {
        m_simulation->pause();
        m_viewport->setFrame(frame);
    });
    connect(m_timeline, &TimelineDock::cacheLeft, this, [this] {
        if (FramePtr live = m_simulation->latestFrame())
            m_viewport->setFrame(std::move(live));
    });

    m_history = new QUndoView(m_document->undoStack());
    m_history->setEmptyLabel(tr("<opened>"));
    QDockWidget* history
        = addPanelDock(tr("History"), QStringLiteral("historyDock"), m_history, Qt::RightDockWidgetArea);
    history->hide();
    QAction* showHistory = history->toggleViewAction();
    showHistory->setText(tr("Undo &History"));
    m_editMenu->addSeparator();
    m_editMenu->addAction(showHistory);
    connect(m_wispPanel, &WispPanel::editRefused, this,
        [this](const QString& why) { statusBar()->showMessage(why, 5000); });

    for (ParameterPanel* panel : { m_forcePanel, m_groomPanel }) {
        connect(panel, &ParameterPanel::valueEdited, this, [this](Param id, double value, bool dragging) {
            const QString refusal = m_document->editParameter(id, value, dragging);
            if (!refusal.isEmpty())
                statusBar()->showMessage(refusal, 5000);
        });
    }
    // Undo, redo and edits all come back through the document.
    const auto parametersEdited = [this] {
        m_forcePanel->setValues(m_document->parameters());
        m_groomPanel->setValues(m_document->parameters());
        m_simulation->setParameters(m_document->parameters());
        showBody();
    };
    connect(m_document, &Document::parameterChanged, this, parametersEdited);
    connect(m_document, &Document::parametersReplaced, this, parametersEdited);
    connect(m_document, &Document::headChanged, this, [this] {
        m_viewport->setHead(m_document->head());
        showBody();
        m_viewport->frameHead();
        m_simulation->setScene(
            m_document->headModel(), m_document->regions(), m_document->soloRegion(), m_document->parameters());
        showGrowthOverlay();
    });
    // Painting, wisp sliders and region edits regroom the running simulation.
    const auto regionsEdited = [this] {
        m_simulation->setRegions(m_document->regions(), m_document->soloRegion());
        showGrowthOverlay();
    };
    connect(m_document, &Document::regionsChanged, this, regionsEdited);
    connect(m_document, &Document::regionParameterChanged, this, regionsEdited);
    connect(m_document, &Document::regionWeightsChanged, this, regionsEdited);
    connect(m_document, &Document::currentRegionChanged, this, &MainWindow::showGrowthOverlay);
    // Salon edits (and their undo) restyle the running hair.
    connect(m_document, &Document::styleChanged, this, [this] { m_simulation->setStyle(m_document->style()); });
}

// The viewport shows the body the simulation collides with (the same defaultBody), while it is on.
void MainWindow::showBody()
{
    m_viewport->setBody(
        m_document->parameters().get(Param::Body) != 0.0 ? defaultBody(m_document->head()) : std::vector<Capsule>{});
}

// The growth weights' tint is for painting: it shows while the paint tool is up or when asked for
// (View > Show Growth Weights), never while a styling tool is (styling shows the head as it is).
void MainWindow::showGrowthTint()
{
    const bool styling = m_styleTool->brush().has_value();
    m_viewport->setShowGrowthOverlay(!styling && (m_paintTool->isActive() || m_overlayAction->isChecked()));
}

void MainWindow::showGrowthOverlay()
{
    const int current = m_document->currentRegion();
    m_viewport->setGrowthOverlay(current >= 0 ? m_document->region(current).weights.toVector() : std::vector<float>{});
    m_viewport->setScalpCoverage(
        scalpCoverage(m_document->regions(), m_document->soloRegion(), m_document->head().positions.size()));
}

void MainWindow::connectSimulation()
{
    connect(
        m_simulation, &SimulationHost::frameReady, this,
        [this] {
            if (!m_timeline->showingCache()) // the cache's frame stays until the artist leaves it
                m_viewport->setFrame(m_simulation->latestFrame());
        },
        Qt::QueuedConnection);
    connect(m_simulation, &SimulationHost::playingChanged, this, &MainWindow::updatePlayAction, Qt::QueuedConnection);
    connect(
        m_simulation, &SimulationHost::errorOccurred, this,
        [this](const QString& message) { statusBar()->showMessage(message, 8000); }, Qt::QueuedConnection);
    // The head follows the document's motion (an edit, undo, a project); a drag sends its own live.
    connect(m_document, &Document::headMotionChanged, this,
        [this] { m_simulation->setHeadMotion(m_document->headMotion()); });
    m_simulation->setHeadMotion(m_document->headMotion());
}

void MainWindow::updatePlayAction(bool playing)
{
    m_viewport->setPaused(!playing);
    m_play->setChecked(playing);
    m_play->setText(playing ? tr("&Pause") : tr("&Play"));
    m_play->setToolTip(playing ? tr("Pause the simulation (Space)") : tr("Play the simulation (Space)"));
    m_play->setIcon(style()->standardIcon(playing ? QStyle::SP_MediaPause : QStyle::SP_MediaPlay));
    m_step->setEnabled(!playing);
    m_step->setIcon(style()->standardIcon(QStyle::SP_MediaSeekForward));
    m_reset->setIcon(style()->standardIcon(QStyle::SP_BrowserReload));
}

void MainWindow::updateTitle()
{
    const QString path = m_fileMenu->projects()->currentPath();
    setWindowFilePath(path);
    setWindowTitle(QStringLiteral("%1[*] — Wisp").arg(path.isEmpty() ? tr("Untitled") : QFileInfo(path).fileName()));
    setWindowModified(!m_document->undoStack()->isClean());
}

void MainWindow::showEvent(QShowEvent* event)
{
    QMainWindow::showEvent(event);
    if (!m_recoveryOffered) {
        m_recoveryOffered = true;
        QTimer::singleShot(0, m_fileMenu, &FileMenu::offerRecovery);
    }
}

void MainWindow::restoreSettings()
{
    QSettings settings;
    if (!restoreGeometry(settings.value(QStringLiteral("window/geometry")).toByteArray()))
        resize(1400, 900);
    restoreState(settings.value(QStringLiteral("window/state")).toByteArray());
}

void MainWindow::saveSettings() const
{
    QSettings settings;
    settings.setValue(QStringLiteral("window/geometry"), saveGeometry());
    settings.setValue(QStringLiteral("window/state"), saveState());
}

void MainWindow::closeEvent(QCloseEvent* event)
{
    if (!m_fileMenu->projects()->maybeSave()) {
        event->ignore();
        return;
    }
    saveSettings();
    m_simulation->pause();
    event->accept();
}

} // namespace wisp
