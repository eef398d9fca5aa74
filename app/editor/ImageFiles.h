#pragma once
// Writing rendered images: one PNG through io/AtomicFile (readers never see half an image, a
// failed write leaves what was there), the names of a turntable's frames, and the check of an
// output path made before any work.
//
// Thread: any.

#include <QImage>
#include <QSize>
#include <QString>

namespace wisp {

// Writes `image` as PNG at `path`, atomically. Empty on success, else "PATH: why".
QString writePngAtomically(const QString& path, const QImage& image);

// Frame `index` (0-based) of an `frames`-frame turntable written to `path` ("out.png"):
// "out_0001.png" … (1-based, at least 4 digits, so the frames sort by name).
QString turntableFramePath(const QString& path, int index, int frames);

// Whether a PNG can be written at `path`: a .png name, not a folder, in an existing folder we may
// write. Empty when it can; else the message, naming the path.
QString checkPngOutput(const QString& path);

// "640x640" -> 640 x 640; each side 1..maxSide. Empty size and `error` set otherwise.
QSize parseImageSize(const QString& text, int maxSide, QString* error);

} // namespace wisp
