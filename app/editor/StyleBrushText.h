#pragma once
// What the artist reads about a salon brush: its name (menus, the panel, its strokes' undo text)
// and how it is used, one line (the panel's hint and the actions' tooltips).
//
// Thread: GUI.

#include "sim/style/BrushContext.h"

#include <QString>

namespace wisp {

QString styleBrushName(StyleBrush brush);
QString styleBrushHelp(StyleBrush brush);

} // namespace wisp
