#include "app/editor/StyleBrushText.h"

#include <QCoreApplication>

namespace wisp {

QString styleBrushName(StyleBrush brush)
{
    switch (brush) {
    case StyleBrush::Comb:
        return QCoreApplication::translate("StyleTool", "Comb");
    case StyleBrush::Cut:
        return QCoreApplication::translate("StyleTool", "Cut");
    case StyleBrush::Length:
        return QCoreApplication::translate("StyleTool", "Grow / Shrink");
    case StyleBrush::Curl:
        return QCoreApplication::translate("StyleTool", "Curl (Perm)");
    case StyleBrush::Wet:
        return QCoreApplication::translate("StyleTool", "Wet");
    case StyleBrush::Hairspray:
        return QCoreApplication::translate("StyleTool", "Hairspray");
    case StyleBrush::BlowDry:
        return QCoreApplication::translate("StyleTool", "Blow-dry");
    }
    return {};
}

QString styleBrushHelp(StyleBrush brush)
{
    switch (brush) {
    case StyleBrush::Comb:
        return QCoreApplication::translate(
            "StyleTool", "Drag through the hair: it follows the comb and rests where you leave it");
    case StyleBrush::Cut:
        return QCoreApplication::translate(
            "StyleTool", "Drag across the hanging hair: every strand the stroke crosses is cut there");
    case StyleBrush::Length:
        return QCoreApplication::translate("StyleTool", "Drag over the hair to grow it; hold Ctrl to shrink it");
    case StyleBrush::Curl:
        return QCoreApplication::translate(
            "StyleTool", "Drag over the hair to perm the touched wisps with the curl below; Ctrl takes the perm out");
    case StyleBrush::Wet:
        return QCoreApplication::translate("StyleTool",
            "Drag over the hair to wet it (heavier, clumped, curls relaxed); it dries over the "
            "drying time; Ctrl towel-dries");
    case StyleBrush::Hairspray:
        return QCoreApplication::translate("StyleTool",
            "Drag over the hair to fix its current shape against gravity and wind; Ctrl washes "
            "the spray out");
    case StyleBrush::BlowDry:
        return QCoreApplication::translate(
            "StyleTool", "Hold the button: air from the cursor along the view pushes and dries the hair");
    }
    return {};
}

} // namespace wisp
