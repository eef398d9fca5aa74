#pragma once
// `wisp --render OUT.png [PROJECT_OR_HEAD] [--size WxH] [--turntable N] [--shadows on|off]
//  [--preset FILE] [--settle SECONDS] [--transparent]`: the editor's view of a scene as a PNG (or a
// turntable of N PNGs, OUT_0001.png …), without showing a window. Runs under xvfb-run.
//
// Everything that can be checked is checked before any work: the arguments, the output's folder,
// the preset and the project (read), the head (read and placed). The hair is then groomed, draped
// and settled for SECONDS of simulated time in fixed steps (SettledScene: deterministic), and the
// images are drawn by Viewport::renderImage, exactly as the editor draws its view.
// Exit status: 0 written; 1 bad input (the message names the argument or file and what is wrong).
//
// Thread: GUI (a QApplication must exist).

#include <QSize>
#include <QString>
#include <QStringList>

#include <optional>

class QTextStream;

namespace wisp {

struct RenderRequest {
    QString output; // .png
    QString input; // a project (.wisp) or a head mesh; empty: the built-in head and hairstyle
    QSize size{ 1280, 720 }; // pixels
    int turntableFrames = 0; // 0: one image; N: N images around the head
    bool shadows = true; // for the viewport's shadows (see runRenderCommand)
    QString preset; // applied after the project or head; empty: none
    double settleSeconds = 2.0; // simulated seconds after the drape
    bool transparent = false; // no background or grid: alpha 0 there
};

// Whether `arguments` (without the program name) ask for a render: they hold --render.
bool wantsRender(const QStringList& arguments);

// The request `arguments` (without the program name) make; nullopt and `error` (naming the
// argument) when they are not one. Only the syntax: files are looked at by runRenderCommand.
std::optional<RenderRequest> parseRenderCommand(const QStringList& arguments, QString* error);

inline constexpr int kMaxTurntableFrames = 3600;
inline constexpr double kMaxSettleSeconds = 600.0;

// Does the render; messages go to `out` (what was written) and `err` (what is wrong). 0 or 1.
int runRenderCommand(const RenderRequest& request, QTextStream& out, QTextStream& err);

} // namespace wisp
