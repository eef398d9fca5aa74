#include "app/editor/RenderActions.h"

#include "app/editor/ImageFiles.h"
#include "app/editor/RenderCommand.h"
#include "widgets/Viewport.h"

#include <QAction>
#include <QCheckBox>
#include <QDialog>
#include <QDialogButtonBox>
#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLineEdit>
#include <QMenu>
#include <QMessageBox>
#include <QProgressDialog>
#include <QPushButton>
#include <QSpinBox>

#include <numbers>

namespace wisp {

RenderActions::RenderActions(QWidget* dialogParent, Viewport* viewport, QMenu* menu)
    : QObject(dialogParent)
    , m_dialogParent(dialogParent)
    , m_viewport(viewport)
{
    m_prompt = [this](const ImageRequest& suggested, bool turntable) {
        return askImageRequest(m_dialogParent, suggested, turntable);
    };
    m_imageAction = menu->addAction(tr("Render &Image…"), this, [this] {
        if (const std::optional<ImageRequest> request = ask(false)) {
            if (const QString error = renderImage(*request); !error.isEmpty())
                QMessageBox::warning(m_dialogParent, tr("Cannot render the image"), error);
        }
    });
    m_imageAction->setToolTip(tr("Write the view as a PNG at a chosen size, at full detail"));
    m_turntableAction = menu->addAction(tr("Render &Turntable…"), this, [this] {
        if (const std::optional<ImageRequest> request = ask(true))
            startTurntable(*request);
    });
    m_turntableAction->setToolTip(tr("Write frames once around the head as a PNG sequence"));
    m_frameTimer.setSingleShot(true);
    m_frameTimer.setInterval(0);
    connect(&m_frameTimer, &QTimer::timeout, this, &RenderActions::renderNextFrame);
}

RenderActions::~RenderActions()
{
    if (m_progress)
        m_progress->disconnect(this);
}

std::optional<RenderActions::ImageRequest> RenderActions::ask(bool turntable)
{
    ImageRequest suggested;
    const QSize view = m_viewport->size() * m_viewport->devicePixelRatioF();
    if (!view.isEmpty())
        suggested.size = view;
    suggested.frames = turntable ? 36 : 1;
    const QString folder = m_lastFolder.isEmpty() ? QDir::homePath() : m_lastFolder;
    suggested.path = QDir(folder).filePath(turntable ? QStringLiteral("turntable.png") : QStringLiteral("render.png"));
    return m_prompt ? m_prompt(suggested, turntable) : std::nullopt;
}

QString RenderActions::renderImage(const ImageRequest& request)
{
    if (QString problem = checkPngOutput(request.path); !problem.isEmpty())
        return problem;
    if (request.size.isEmpty() || request.size.width() > Viewport::kMaxImageSide
        || request.size.height() > Viewport::kMaxImageSide)
        return tr("%1 x %2: each side must be 1 to %3 pixels")
            .arg(request.size.width())
            .arg(request.size.height())
            .arg(Viewport::kMaxImageSide);
    Viewport::ImageOptions options;
    options.transparentBackground = request.transparent;
    const QImage image = m_viewport->renderImage(request.size, options);
    if (QString error = writePngAtomically(request.path, image); !error.isEmpty())
        return error;
    m_lastFolder = QFileInfo(request.path).absolutePath();
    emit message(tr("Rendered %1 (%2 x %3)").arg(request.path).arg(image.width()).arg(image.height()));
    return {};
}

bool RenderActions::startTurntable(const ImageRequest& request)
{
    QString problem;
    if (m_turntable)
        problem = tr("A turntable is already being rendered");
    else if (request.frames < 1 || request.frames > kMaxTurntableFrames)
        problem = tr("%1 frames: a turntable has 1 to %2").arg(request.frames).arg(kMaxTurntableFrames);
    else if (request.size.isEmpty() || request.size.width() > Viewport::kMaxImageSide
        || request.size.height() > Viewport::kMaxImageSide)
        problem = tr("each side must be 1 to %1 pixels").arg(Viewport::kMaxImageSide);
    else
        problem = checkPngOutput(request.path);
    if (!problem.isEmpty()) {
        emit message(problem);
        return false;
    }
    m_turntable = Turntable{ request, 0 };
    m_progress = new QProgressDialog(tr("Rendering the turntable…"), tr("Cancel"), 0, request.frames, m_dialogParent);
    m_progress->setWindowTitle(tr("Render Turntable"));
    m_progress->setAttribute(Qt::WA_DeleteOnClose);
    m_progress->setAutoClose(false);
    m_progress->setAutoReset(false);
    m_progress->setMinimumDuration(0);
    connect(m_progress, &QProgressDialog::canceled, this, &RenderActions::cancelTurntable);
    m_progress->setValue(0);
    m_progress->show();
    m_frameTimer.start();
    return true;
}

void RenderActions::cancelTurntable()
{
    if (m_turntable)
        finishTurntable(true, {});
}

void RenderActions::renderNextFrame()
{
    if (!m_turntable)
        return;
    Turntable& job = *m_turntable;
    const int frames = job.request.frames;
    Viewport::ImageOptions options;
    options.transparentBackground = job.request.transparent;
    options.turnRadians = 2.0f * std::numbers::pi_v<float> * static_cast<float>(job.next) / static_cast<float>(frames);
    const QImage image = m_viewport->renderImage(job.request.size, options);
    if (QString error = writePngAtomically(turntableFramePath(job.request.path, job.next, frames), image);
        !error.isEmpty()) {
        finishTurntable(false, error);
        return;
    }
    ++job.next;
    if (m_progress)
        m_progress->setValue(job.next);
    if (job.next >= frames) {
        finishTurntable(false, {});
        return;
    }
    m_frameTimer.start();
}

void RenderActions::finishTurntable(bool cancelled, const QString& error)
{
    m_frameTimer.stop();
    const ImageRequest request = m_turntable->request;
    const int written = m_turntable->next;
    m_turntable.reset();
    if (m_progress) {
        m_progress->disconnect(this); // closing it says canceled(): not the artist's
        m_progress->close();
        m_progress = nullptr;
    }
    m_lastFolder = QFileInfo(request.path).absolutePath();
    if (!error.isEmpty())
        emit message(error);
    else if (cancelled)
        emit message(tr("Turntable cancelled after %1 of %2 frames").arg(written).arg(request.frames));
    else
        emit message(tr("Rendered %1 turntable frames: %2 …")
                         .arg(written)
                         .arg(turntableFramePath(request.path, 0, request.frames)));
    emit turntableFinished(written, cancelled, error);
}

std::optional<RenderActions::ImageRequest> askImageRequest(
    QWidget* parent, const RenderActions::ImageRequest& suggested, bool turntable)
{
    QDialog dialog(parent);
    dialog.setWindowTitle(turntable ? QObject::tr("Render Turntable") : QObject::tr("Render Image"));
    auto* form = new QFormLayout(&dialog);
    auto* path = new QLineEdit(suggested.path);
    auto* browse = new QPushButton(QObject::tr("Browse…"));
    auto* pathRow = new QHBoxLayout;
    pathRow->addWidget(path, 1);
    pathRow->addWidget(browse);
    form->addRow(turntable ? QObject::tr("First of the files") : QObject::tr("File"), pathRow);
    QObject::connect(browse, &QPushButton::clicked, &dialog, [&dialog, path] {
        const QString chosen = QFileDialog::getSaveFileName(
            &dialog, QObject::tr("Render to"), path->text(), QObject::tr("PNG images (*.png)"));
        if (!chosen.isEmpty())
            path->setText(chosen.endsWith(QStringLiteral(".png"), Qt::CaseInsensitive) ? chosen : chosen + ".png");
    });
    auto* width = new QSpinBox;
    auto* height = new QSpinBox;
    for (QSpinBox* box : { width, height }) {
        box->setRange(1, Viewport::kMaxImageSide);
        box->setSuffix(QObject::tr(" px"));
    }
    width->setValue(suggested.size.width());
    height->setValue(suggested.size.height());
    form->addRow(QObject::tr("Width"), width);
    form->addRow(QObject::tr("Height"), height);
    auto* frames = new QSpinBox;
    frames->setRange(1, kMaxTurntableFrames);
    frames->setValue(suggested.frames);
    if (turntable)
        form->addRow(QObject::tr("Frames"), frames);
    auto* transparent = new QCheckBox(QObject::tr("Transparent background"));
    transparent->setChecked(suggested.transparent);
    form->addRow(transparent);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
    form->addRow(buttons);
    QObject::connect(buttons, &QDialogButtonBox::accepted, &dialog, &QDialog::accept);
    QObject::connect(buttons, &QDialogButtonBox::rejected, &dialog, &QDialog::reject);
    if (dialog.exec() != QDialog::Accepted)
        return std::nullopt;
    RenderActions::ImageRequest request;
    request.path = path->text();
    request.size = QSize(width->value(), height->value());
    request.transparent = transparent->isChecked();
    request.frames = turntable ? frames->value() : 1;
    return request;
}

} // namespace wisp
