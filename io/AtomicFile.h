#pragma once
// The one way Wisp writes a file (projects and their .bak, autosaves, presets, hair, strand text):
// readers see the old content or the new, never half, and a process killed at any moment leaves
// the old file or the new one plus, at worst, a temporary file that the next start removes.
//
// How: the content goes to "<name>.<16 random hex digits>.tmp-<pid>" in the folder of the file it
// replaces, created with O_CREAT|O_EXCL (a file or symbolic link already at that name is never
// opened, so nothing planted there can redirect the write) and with the replaced file's permissions
// (a 0600 file stays 0600; a new file gets 0666 less the umask). The temporary is fsync'ed, renamed
// over the file, then the folder is fsync'ed. A symbolic link stays a link: the file it ends at is
// replaced. On any error the temporary is removed, the old file is untouched and the message names
// the path and the system's reason. The pid in the name tells removeStaleTemporaryFiles whose it is.
//
// Thread safety: any thread; files of different names may be written at once.

#include "io/IoError.h"

#include <cstddef>
#include <functional>
#include <ostream>
#include <string>

namespace wisp::io {

// `write` fills the stream; returns success, or an IoError naming `path` and what went wrong (why).
// An exception thrown by `write` removes the temporary and passes on.
Result<void> writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write);

// Makes `copyPath` hold what `source` holds now, with `source`'s permissions, replacing any file
// there without a moment when neither exists: a hard link under a temporary name (a copy through
// writeFileAtomically where links are not possible), renamed over `copyPath`. The error names `copyPath`.
Result<void> keepCopyAtomically(const std::string& source, const std::string& copyPath);

// The file a write to `path` replaces: `path`, or the end of its chain of symbolic links. A link
// that leads nowhere gives where it points; a loop (or more than 40 links) gives "" and `error`.
std::string writeTargetOf(const std::string& path, std::string* error = nullptr);

// Removes, in `folder` (not below it), the temporary files of writers that died: names
// "<name>.<16 hex>.tmp-<pid>", and the older "<name>.tmp-<pid>" when <name> is beside it, whose
// process is gone. Temporaries of live processes stay. Returns how many were removed.
std::size_t removeStaleTemporaryFiles(const std::string& folder);

// Whether process `pid` exists (on this machine). Not a pid (<= 0) is not alive.
bool isProcessAlive(long pid);

namespace detail {
// Tests only: the random part of the next temporary names comes from `next` (nullptr: the system's
// random source), so a test can plant a file at the exact name the writer will try first.
void setTemporaryNameSourceForTests(std::function<std::string()> next);
} // namespace detail

} // namespace wisp::io
