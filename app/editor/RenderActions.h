#pragma once
// File ▸ Render Image… and File ▸ Render Turntable…: the viewport's view (Viewport::renderImage,
// full detail, no overlays) as a PNG of a chosen size, with an optional transparent background, or
// as N PNGs once around the head (NAME_0001.png …) with a progress dialog whose Cancel stops it.
//
// The questions (file, size, frames) are asked by a prompt that tests replace (setImagePrompt,
// setTurntablePrompt), so no dialog is ever left open by a test; renderImage() and startTurntable()
// are the paths without questions. A turntable draws one frame per turn of the event loop, so the
// window keeps drawing and Cancel is heard between frames.
//
// Thread: GUI.

#include <QObject>
#include <QPointer>
#include <QProgressDialog>
#include <QSize>
#include <QString>
#include <QTimer>

#include <functional>
#include <optional>

class QAction;
class QMenu;
class QWidget;

namespace wisp {

class Viewport;

class RenderActions : public QObject {
    Q_OBJECT
public:
    struct ImageRequest {
        QString path;
        QSize size{ 1280, 720 };
        bool transparent = false;
        int frames = 1; // turntables: the number of frames around the head
    };
    // Asks for a request; nullopt: the artist cancelled.
    using Prompt = std::function<std::optional<ImageRequest>(const ImageRequest& suggested, bool turntable)>;

    RenderActions(QWidget* dialogParent, Viewport* viewport, QMenu* menu);
    ~RenderActions() override;

    QAction* renderImageAction() const { return m_imageAction; }
    QAction* renderTurntableAction() const { return m_turntableAction; }
    void setPrompt(Prompt prompt) { m_prompt = std::move(prompt); }

    // Writes one image; the error (naming the file), or empty when written.
    QString renderImage(const ImageRequest& request);
    // Starts a turntable of request.frames frames (refused while one runs, or for a bad request:
    // false and message()).
    bool startTurntable(const ImageRequest& request);
    void cancelTurntable();
    bool turntableRunning() const { return m_turntable.has_value(); }
    QProgressDialog* progressDialog() const { return m_progress; } // while a turntable runs

signals:
    void message(const QString& text);
    // A turntable ended: the frames it wrote, and whether it was cancelled or failed (error).
    void turntableFinished(int framesWritten, bool cancelled, const QString& error);

private:
    struct Turntable {
        ImageRequest request;
        int next = 0;
    };
    std::optional<ImageRequest> ask(bool turntable);
    void renderNextFrame();
    void finishTurntable(bool cancelled, const QString& error);

    QWidget* m_dialogParent;
    Viewport* m_viewport;
    QAction* m_imageAction = nullptr;
    QAction* m_turntableAction = nullptr;
    Prompt m_prompt;
    std::optional<Turntable> m_turntable;
    QPointer<QProgressDialog> m_progress;
    QTimer m_frameTimer;
    QString m_lastFolder;
};

// The default prompt: a small dialog (file, width, height, transparent background, frames).
std::optional<RenderActions::ImageRequest> askImageRequest(
    QWidget* parent, const RenderActions::ImageRequest& suggested, bool turntable);

} // namespace wisp
