#include "app/editor/ImageFiles.h"

#include "io/AtomicFile.h"

#include <QBuffer>
#include <QByteArray>
#include <QFileInfo>
#include <QRegularExpression>

#include <algorithm>

namespace wisp {

QString writePngAtomically(const QString& path, const QImage& image)
{
    if (image.isNull())
        return path + QStringLiteral(": no image to write (the view could not be drawn)");
    QByteArray bytes;
    QBuffer buffer(&bytes);
    buffer.open(QIODevice::WriteOnly);
    if (!image.save(&buffer, "PNG"))
        return path + QStringLiteral(": could not encode the image as PNG");
    const io::Result<void> written = io::writeFileAtomically(path.toStdString(),
        [&bytes](std::ostream& out) { out.write(bytes.constData(), static_cast<std::streamsize>(bytes.size())); });
    return written ? QString() : QString::fromStdString(written.error().toString());
}

QString turntableFramePath(const QString& path, int index, int frames)
{
    const QFileInfo info(path);
    const int digits = std::max(4, static_cast<int>(QString::number(std::max(frames, 1)).size()));
    const QString name = QStringLiteral("%1_%2.%3")
                             .arg(info.completeBaseName())
                             .arg(index + 1, digits, 10, QLatin1Char('0'))
                             .arg(info.suffix().isEmpty() ? QStringLiteral("png") : info.suffix());
    return path.left(path.lastIndexOf(QLatin1Char('/')) + 1) + name; // the folder exactly as given
}

QString checkPngOutput(const QString& path)
{
    if (path.isEmpty())
        return QStringLiteral("no output file named");
    const QFileInfo info(path);
    if (info.suffix().compare(QStringLiteral("png"), Qt::CaseInsensitive) != 0)
        return path + QStringLiteral(": the output must be a .png file");
    if (info.isDir())
        return path + QStringLiteral(": is a folder, not a file");
    const QFileInfo folder(info.absolutePath());
    if (!folder.exists() || !folder.isDir())
        return path + QStringLiteral(": the folder %1 does not exist").arg(info.absolutePath());
    if (!folder.isWritable())
        return path + QStringLiteral(": the folder %1 is not writable").arg(info.absolutePath());
    if (info.exists() && !info.isFile())
        return path + QStringLiteral(": is not a regular file");
    return {};
}

QSize parseImageSize(const QString& text, int maxSide, QString* error)
{
    static const QRegularExpression pattern(QStringLiteral("^\\s*(\\d{1,6})\\s*[xX×]\\s*(\\d{1,6})\\s*$"));
    const QRegularExpressionMatch match = pattern.match(text);
    const auto refuse = [&](const QString& why) {
        if (error)
            *error = why;
        return QSize();
    };
    if (!match.hasMatch())
        return refuse(QStringLiteral("--size %1: not WIDTHxHEIGHT in pixels (e.g. 640x640)").arg(text));
    const int w = match.captured(1).toInt();
    const int h = match.captured(2).toInt();
    if (w < 1 || h < 1 || w > maxSide || h > maxSide)
        return refuse(QStringLiteral("--size %1: each side must be 1 to %2 pixels").arg(text).arg(maxSide));
    return QSize(w, h);
}

} // namespace wisp
