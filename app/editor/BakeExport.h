#pragma once
// A finished bake written out: USD text (.usda, every frame a time sample of the strands, the head
// as a mesh with its motion; io/UsdaWriter.h) or a cyHair .hair sequence (PATTERN with # for the
// frame number, one file per frame; io/FramePattern.h). The same writers as `wisp-cli bake`.
//
// Thread: any (the editor calls it on the GUI thread; a cache of a few hundred frames of the
// default scene writes in well under a second per frame).

#include "app/editor/BakeController.h"

#include <QString>

namespace wisp {

// Writes `baked` to `path` (.usda, or .hair with # in the file name). Returns the error, naming the
// file; empty on success. `filesWritten` (may be null) says how many files were written: a .hair
// sequence that fails part-way keeps the frames before the failing one, each complete.
QString exportBake(const BakedScene& baked, const QString& path, int* filesWritten = nullptr);

} // namespace wisp
