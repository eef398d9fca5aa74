#include "app/editor/ListMark.h"

#include <QPainter>
#include <QPixmap>

namespace wisp {

QIcon listMark(const QColor& colour, ListMarkShape shape)
{
    QPixmap pixmap(kListMarkSizePx, kListMarkSizePx);
    pixmap.fill(Qt::transparent);
    if (colour.isValid()) {
        QPainter painter(&pixmap);
        painter.setRenderHint(QPainter::Antialiasing);
        painter.setPen(Qt::NoPen);
        painter.setBrush(colour);
        if (shape == ListMarkShape::Dot)
            painter.drawEllipse(QRectF(3.0, 3.0, kListMarkSizePx - 6.0, kListMarkSizePx - 6.0));
        else
            painter.drawRoundedRect(QRectF(4.0, 4.0, kListMarkSizePx - 8.0, kListMarkSizePx - 8.0), 1.5, 1.5);
    }
    return QIcon(pixmap);
}

} // namespace wisp
