#pragma once

#include <QColor>
#include <QIcon>

namespace wisp {

// The small marks that list rows carry (a region's solo dot, a bundled preset's square), drawn
// one way so they match. An invalid colour gives a blank icon of the same size, so that rows with
// and without a mark keep their names lined up.
enum class ListMarkShape { Dot, Square };

// The marks' side in pixels: a list's default icon size.
constexpr int kListMarkSizePx = 16;

QIcon listMark(const QColor& colour, ListMarkShape shape);

} // namespace wisp
