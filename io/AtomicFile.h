#pragma once
// Writes a file so that readers see either the old content or the new, never half of it:
// everything goes to "<path>.tmp-<pid>", which is flushed and renamed over `path`.

#include <functional>
#include <ostream>
#include <string>

namespace wisp::io {

// `write` fills the stream; returns an empty string on success, or what went wrong (naming the file).
std::string writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write);

}  // namespace wisp::io
