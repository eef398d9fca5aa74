#pragma once
// Checks an output path before any work is done: a bad path or an unknown extension used to be
// found only after the whole simulation (6-9 s wasted). Every wisp-cli command that writes calls
// this first.

#include <string>
#include <vector>

namespace wisp::cli {

// Throws CliError{kBadInput} naming `what` ("--export", "OUT") and the path when: the extension
// is not in `extensions` (lower case, no dot; empty list: any extension), the path is a folder,
// or its folder does not exist, is not a folder, or cannot be written to.
void checkOutputPath(const std::string& path, const std::string& what, const std::vector<std::string>& extensions);

} // namespace wisp::cli
