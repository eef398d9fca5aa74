#pragma once
// The one way io/ reads a whole file. Every reader goes through it, so every reader refuses the
// same things with the same words: a missing file, a folder, anything that is not a regular file
// (a FIFO would block the reader forever, /dev/zero would never end) and a file larger than the
// reader's cap. The file is opened non-blocking and checked with fstat on the open descriptor, so
// a regular file swapped for a FIFO between a check and the open cannot block either.

#include "io/IoError.h"

#include <cstdint>
#include <string>

namespace wisp::io {

// Caps by kind of file: far above any real file of that kind, far below what would hurt.
inline constexpr std::uint64_t kMaxMeshFileBytes = std::uint64_t{ 2 } << 30; // 2 GiB: a 270k-triangle scan is 10 MB
inline constexpr std::uint64_t kMaxHairFileBytes = std::uint64_t{ 2 } << 30; // 2 GiB: cyHair's 50k strands are 60 MB
inline constexpr std::uint64_t kMaxTextFileBytes = std::uint64_t{ 1 } << 20; // 1 MiB: parameter files
inline constexpr std::uint64_t kMaxStrandTextBytes = std::uint64_t{ 1 } << 30; // 1 GiB: wisp-strands text

struct RegularFileRules {
    std::uint64_t maxBytes = kMaxMeshFileBytes;
    const char* what = "mesh"; // "this is a folder, not a <what> file"
    bool allowEmpty = false;
};

// The whole file, or an IoError (file = `path`, no location) saying why not.
Result<std::string> readRegularFile(const std::string& path, const RegularFileRules& rules);

// The same, for parsers that report through io::ReadFailure (io/ReadFailure.h): throws it
// (location and message of the IoError above) instead of returning it.
std::string readRegularFileOrFail(const std::string& path, const RegularFileRules& rules);

// The file name's extension in lower case, without the dot: "HEAD.OBJ" gives "obj"; "" if none.
std::string lowerExtension(const std::string& path);

// "13 MB": whole mebibytes, rounded up
std::string megabytesText(std::uint64_t bytes);

} // namespace wisp::io
