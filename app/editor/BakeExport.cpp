#include "app/editor/BakeExport.h"

#include "io/FramePattern.h"
#include "io/HairFiles.h"
#include "io/UsdaWriter.h"

#include <QFileInfo>

namespace wisp {

namespace {

// Per drawn strand: its region's hair thickness at the root (the viewport's 80 µm where a region
// gives none), as `wisp-cli bake` writes it.
std::vector<float> rootWidths(const BakedScene& baked)
{
    const Frame& look = baked.look;
    std::vector<float> widths(baked.cache.offsets.size() - 1, 80e-6f);
    for (std::size_t s = 0; s < widths.size() && s < look.lookOfStrand.size(); ++s)
        if (look.lookOfStrand[s] < look.looks.size() && look.looks[look.lookOfStrand[s]].rootThicknessMetres > 0.0f)
            widths[s] = look.looks[look.lookOfStrand[s]].rootThicknessMetres;
    return widths;
}

} // namespace

QString exportBake(const BakedScene& baked, const QString& path, int* filesWritten)
{
    if (filesWritten)
        *filesWritten = 0;
    const BakeCache& cache = baked.cache;
    if (cache.frames.empty())
        return QObject::tr("%1: the bake has no frames").arg(path);
    const QString suffix = QFileInfo(path).suffix().toLower();
    const std::string file = path.toStdString();
    if (suffix == QStringLiteral("usda")) {
        io::UsdaScene scene;
        scene.offsets = cache.offsets;
        scene.widthsMetres = io::taperedWidths(scene.offsets, rootWidths(baked), 0.25f);
        scene.framesPerSecond = cache.range.fps;
        scene.animated = cache.frames.size() > 1;
        scene.head = baked.head ? &baked.head->mesh() : nullptr;
        for (const BakedFrame& f : cache.frames)
            scene.frames.push_back({ static_cast<double>(f.frame), f.positions, f.headToWorld });
        if (const io::Result<void> written = io::writeUsda(file, scene); !written)
            return QString::fromStdString(written.error().toString());
        if (filesWritten)
            *filesWritten = 1;
        return {};
    }
    if (suffix == QStringLiteral("hair")) {
        if (!io::isFramePattern(file))
            return QObject::tr("%1: a .hair sequence needs # in the file name for the frame number "
                               "(e.g. hair.####.hair)")
                .arg(path);
        for (const BakedFrame& f : cache.frames) {
            HairCurves curves;
            curves.offsets = cache.offsets;
            curves.positions = f.positions;
            if (const io::Result<void> written = io::writeHair(io::framePath(file, f.frame), curves); !written)
                return QString::fromStdString(written.error().toString());
            if (filesWritten)
                ++*filesWritten;
        }
        return {};
    }
    return QObject::tr("%1: a bake is exported as .usda or as a .hair sequence (hair.####.hair)").arg(path);
}

} // namespace wisp
