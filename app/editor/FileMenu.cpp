#include "app/editor/FileMenu.h"

#include "app/editor/Document.h"
#include "app/editor/ExportHairDialog.h"
#include "app/editor/HeadImporter.h"
#include "app/editor/ProjectController.h"
#include "app/editor/RenderActions.h"
#include "app/editor/SimulationHost.h"
#include "io/HairFiles.h"
#include "io/HeadPlacement.h"
#include "io/MeshReader.h"
#include "io/StrandPlacement.h"
#include "sim/groom/GrowthMap.h"
#include "widgets/Viewport.h"

#include <QAbstractButton>
#include <QAction>
#include <QActionGroup>
#include <QDateTime>
#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QInputDialog>
#include <QMainWindow>
#include <QMenu>
#include <QMenuBar>
#include <QMessageBox>
#include <QPushButton>

namespace wisp {

namespace {

QString patternsOf(const std::vector<std::string>& extensions)
{
    QStringList patterns;
    for (const std::string& ext : extensions)
        patterns << QStringLiteral("*.%1").arg(QString::fromStdString(ext));
    return patterns.join(' ');
}

} // namespace

FileMenu::FileMenu(QMainWindow* window, Document* document, SimulationHost* simulation, Viewport* viewport)
    : QObject(window)
    , m_window(window)
    , m_document(document)
    , m_simulation(simulation)
    , m_viewport(viewport)
    , m_projects(new ProjectController(document, viewport, window))
    , m_importer(new HeadImporter(window))
{
    buildMenu();
    connect(m_projects, &ProjectController::message, this, &FileMenu::message);
    connect(m_projects, &ProjectController::recentFilesChanged, this, &FileMenu::rebuildRecentMenu);
    connect(m_importer, &HeadImporter::imported, this, &FileMenu::takeHead);
    connect(m_importer, &HeadImporter::failed, this, [this](const QString& why) { warn(tr("Cannot open head"), why); });
}

FileMenu::~FileMenu() = default;

void FileMenu::buildMenu()
{
    m_menu = m_window->menuBar()->addMenu(tr("&File"));
    m_menu->addAction(tr("&New Project"), QKeySequence::New, this, [this] { m_projects->newProject(); });
    m_menu->addAction(tr("&Open Project…"), QKeySequence::Open, this, [this] { m_projects->open(); });
    m_recentMenu = m_menu->addMenu(tr("Open &Recent"));
    rebuildRecentMenu();
    m_menu->addAction(tr("&Save"), QKeySequence::Save, this, [this] { m_projects->save(); });
    m_saveAs = m_menu->addAction(tr("Save &As…"), this, [this] { m_projects->saveAs(); });
    // Ctrl+Shift+S everywhere: the platform's Save As keys are empty on some desktops (KDE, plain X11).
    QList<QKeySequence> saveAsKeys{ QKeySequence(tr("Ctrl+Shift+S")) };
    for (const QKeySequence& key : QKeySequence::keyBindings(QKeySequence::SaveAs))
        if (!saveAsKeys.contains(key))
            saveAsKeys.push_back(key);
    m_saveAs->setShortcuts(saveAsKeys);
    m_menu->addSeparator();

    m_menu->addAction(tr("Open &Head…"), QKeySequence(tr("Ctrl+Shift+O")), this, [this] {
        const QString path = QFileDialog::getOpenFileName(
            m_window, tr("Open Head"), QString(), tr("Meshes (%1)").arg(patternsOf(io::supportedMeshExtensions())));
        if (!path.isEmpty())
            openHead(path);
    });
    QAction* scale = m_menu->addAction(tr("Head &Scale…"), this, &FileMenu::changeHeadScale);
    scale->setToolTip(tr("The imported head's metres per file unit"));
    m_upMenu = m_menu->addMenu(tr("Head &Up Axis"));
    m_upMenu->setToolTipsVisible(true);
    auto* upGroup = new QActionGroup(m_upMenu);
    const auto addUp = [&](const QString& text, std::optional<io::Axis> up) {
        QAction* action = m_upMenu->addAction(text);
        action->setCheckable(true);
        action->setData(up ? QVariant(static_cast<int>(*up)) : QVariant());
        upGroup->addAction(action);
        connect(action, &QAction::triggered, this, [this, up] {
            if (m_lastHead)
                placeAgain(m_lastHead->placement.scale, up);
        });
    };
    addUp(tr("From Its Shape"), std::nullopt);
    m_upMenu->actions().front()->setToolTip(
        tr("Find up and the face from the head itself: its mirror symmetry, its nose, the skull above the nose"));
    m_upMenu->addSeparator();
    for (io::Axis up :
        { io::Axis::PosY, io::Axis::PosZ, io::Axis::NegZ, io::Axis::PosX, io::Axis::NegX, io::Axis::NegY })
        addUp(QString::fromLatin1(io::axisName(up)), up);
    m_upMenu->actions().front()->setChecked(true);
    m_menu->addSeparator();
    m_menu->addAction(tr("&Import Hair…"), this, [this] {
        const QString path = QFileDialog::getOpenFileName(
            m_window, tr("Import Hair"), QString(), tr("Hair (%1)").arg(patternsOf(io::hairReadExtensions())));
        if (!path.isEmpty())
            importHair(path);
    });
    m_menu->addAction(tr("&Export Hair…"), QKeySequence(tr("Ctrl+E")), this, [this] {
        ExportHairDialog dialog(m_window);
        if (dialog.exec() != QDialog::Accepted)
            return;
        const HairExportChoice choice = dialog.choice();
        if (const QString error = exportHair(dialog.path(), choice.restPose, choice.keysOnly); !error.isEmpty())
            QMessageBox::warning(m_window, tr("Cannot export hair"), error);
    });
    m_menu->addSeparator();
    m_render = new RenderActions(m_window, m_viewport, m_menu);
    connect(m_render, &RenderActions::message, this, &FileMenu::message);
    m_menu->addSeparator();
    m_menu->addAction(tr("&Quit"), QKeySequence::Quit, m_window, &QWidget::close);
}

void FileMenu::rebuildRecentMenu()
{
    m_recentMenu->clear();
    const QStringList recent = m_projects->recentFiles();
    for (const QString& path : recent)
        m_recentMenu->addAction(QFileInfo(path).fileName(), this, [this, path] { m_projects->open(path); })
            ->setToolTip(path);
    m_recentMenu->setEnabled(!recent.isEmpty());
}

bool FileMenu::openAny(const QString& path)
{
    const QString suffix = QFileInfo(path).suffix().toLower();
    if (suffix == QLatin1String("wisp"))
        return m_projects->open(path);
    return openHead(path);
}

bool FileMenu::openHead(const QString& path)
{
    return m_importer->start(path);
}

void FileMenu::takeHead(const std::shared_ptr<const ImportedHead>& head)
{
    m_lastHead = head;
    for (QAction* action : m_upMenu->actions())
        if (action->isCheckable())
            action->setChecked(head->chosenUp ? action->data() == QVariant(static_cast<int>(*head->chosenUp))
                                              : !action->data().isValid());
    m_upMenu->setEnabled(!io::formatFixesUpAxis(head->path.toStdString()));
    TriangleMesh mesh = head->mesh;
    std::vector<float> weights = scalpGrowth(mesh);
    m_document->replaceHead(
        std::move(mesh), std::move(weights), QFileInfo(head->path).fileName(), head->path, head->placement);
    QString text = QFileInfo(head->path).fileName() + QStringLiteral(": ")
        + QString::fromStdString(io::describePlacement(head->placement));
    if (!head->placement.note.empty())
        text += QStringLiteral(" · ") + tr("check: %1").arg(QString::fromStdString(head->placement.note));
    if (!head->warnings.isEmpty())
        text += QStringLiteral(" · ") + head->warnings.join(QStringLiteral(" · "));
    emit message(text);
}

void FileMenu::changeHeadScale()
{
    if (!m_lastHead) {
        QMessageBox::information(
            m_window, tr("Head Scale"), tr("The scale applies to a head opened from a file (File ▸ Open Head)."));
        return;
    }
    bool ok = false;
    const double scale = QInputDialog::getDouble(m_window, tr("Head Scale"),
        tr("%1\nMetres per file unit (0.001 millimetres, 0.01 centimetres, 1 metres):")
            .arg(QString::fromStdString(io::describePlacement(m_lastHead->placement))),
        m_lastHead->placement.scale, 1e-6, 1e3, 6, &ok);
    if (!ok)
        return;
    placeAgain(static_cast<float>(scale), m_lastHead->chosenUp);
}

bool FileMenu::placeAgain(float scale, std::optional<io::Axis> up)
{
    if (!m_lastHead || !(scale > 0.0f))
        return false;
    auto head = std::make_shared<ImportedHead>(*m_lastHead);
    head->mesh = head->asRead;
    io::HeadPlacementSettings settings;
    settings.explicitScale = scale;
    head->chosenUp = up;
    settings.up = io::formatFixesUpAxis(head->path.toStdString()) ? std::optional(io::Axis::PosY) : up;
    head->placement = io::placeHead(head->mesh, settings);
    // The same check as Open Head: a scale that makes the head flat or kilometres wide is refused
    // and the head stays as it was.
    if (std::string problem = io::checkPlacedHead(head->mesh); !problem.empty()) {
        const QString text = tr("%1: %2").arg(QFileInfo(head->path).fileName(), QString::fromStdString(problem));
        emit message(text);
        if (m_interactive)
            QMessageBox::warning(m_window, tr("Head Scale"), text);
        return false;
    }
    takeHead(head);
    return true;
}

QString FileMenu::importHair(const QString& path)
{
    io::Result<io::HairReadResult> read = io::readHair(path.toStdString());
    if (!read) {
        const QString error = QString::fromStdString(read.error().toString());
        warn(tr("Cannot import hair"), error);
        return error;
    }
    io::HairReadResult result = std::move(read).value();
    // Strands come in the units and axes of the file they were made with, like the head that came
    // with them: the head's placement brings both to Wisp's metres, +Y up; on the built-in head
    // only their unit is guessed. The same function as wisp-cli simulate --hair.
    const bool headFromFile = !m_document->headSource().isEmpty();
    const io::StrandPlacement placed
        = io::placeStrands(result.strands, headFromFile ? &m_document->headPlacement() : nullptr);
    auto strands = std::make_shared<const HairCurves>(std::move(result.strands));
    m_document->addImportedHair(strands, QFileInfo(path).fileName());
    QString text = tr("Imported %1 strands from %2: %3")
                       .arg(strands->strandCount())
                       .arg(QFileInfo(path).fileName(), QString::fromStdString(placed.description));
    if (!placed.note.empty())
        text += QStringLiteral(" · ") + tr("check: %1").arg(QString::fromStdString(placed.note));
    for (const std::string& w : result.warnings)
        text += QStringLiteral(" · ") + QString::fromStdString(w);
    emit message(text);
    return {};
}

QString FileMenu::exportHair(const QString& path, bool restPose, bool keysOnly)
{
    const FramePtr frame = m_simulation->latestFrame();
    if (!frame)
        return tr("there is no hair to export yet");
    const HairCurves strands = strandsForExport(*frame, { restPose, keysOnly });
    io::HairExportOptions options;
    options.head = &m_document->head();
    if (const io::Result<void> written = io::writeHair(path.toStdString(), strands, options); !written)
        return QString::fromStdString(written.error().toString());
    emit message(tr("Exported %1 strands to %2").arg(strands.strandCount()).arg(QDir::toNativeSeparators(path)));
    return {};
}

void FileMenu::setInteractive(bool interactive)
{
    m_interactive = interactive;
    m_projects->setInteractive(interactive);
}

void FileMenu::warn(const QString& title, const QString& text)
{
    if (m_interactive)
        QMessageBox::warning(m_window, title, text);
    emit message(text);
}

void FileMenu::offerRecovery()
{
    if (!m_projects->recoveryAvailable() || (!m_recoveryPrompt && !m_interactive))
        return;
    const QString project = m_projects->recoveryProjectPath();
    const QString when = QFileInfo(m_projects->recoveryAutosavePath()).lastModified().toString(Qt::TextDate);
    const QString question = project.isEmpty()
        ? tr("Wisp did not close properly last time. Recover the untitled project it saved automatically "
             "(%1)?")
              .arg(when)
        : tr("Wisp did not close properly last time. Recover the unsaved changes to %1 that it saved "
             "automatically (%2)?")
              .arg(QDir::toNativeSeparators(project), when);
    RecoveryAnswer answer = RecoveryAnswer::Later;
    if (m_recoveryPrompt) {
        answer = m_recoveryPrompt(question);
    } else {
        QMessageBox box(QMessageBox::Question, tr("Recover work"), question, QMessageBox::NoButton, m_window);
        QAbstractButton* recover = box.addButton(tr("Recover"), QMessageBox::AcceptRole);
        QAbstractButton* discard = box.addButton(QMessageBox::Discard);
        box.addButton(tr("Later"), QMessageBox::RejectRole); // Esc: keep it for the next start
        box.setDefaultButton(qobject_cast<QPushButton*>(recover));
        box.exec();
        answer = box.clickedButton() == recover ? RecoveryAnswer::Recover
            : box.clickedButton() == discard    ? RecoveryAnswer::Discard
                                                : RecoveryAnswer::Later;
    }
    if (answer == RecoveryAnswer::Recover)
        m_projects->recover();
    else if (answer == RecoveryAnswer::Discard)
        m_projects->discardRecovery();
}

} // namespace wisp
