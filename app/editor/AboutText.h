#pragma once
// What Help > About Wisp says: what Wisp is, and what it runs on here, for a bug report: the CPU by
// its maker's name, the SIMD target the solver's kernels were given at run time for it (one binary
// runs SSE4, AVX2 or AVX-512 code, README "One binary for every CPU"), Qt, and the OpenGL the view
// draws with.

#include <QString>

namespace wisp {

// Rich text for QMessageBox::about. `glDescription`: the view's (Viewport::glDescription), empty
// while it has no context yet.
QString aboutText(const QString& glDescription);

} // namespace wisp
