#pragma once
// The one error type io/'s parsers throw inside themselves. A reader parses top to bottom and
// calls fail() where it finds a problem; its public entry point catches the ReadFailure and
// returns it as an IoError with the file's path (io/IoError.h). Nothing outside io/ sees it.

#include <cstdint>
#include <string>

namespace wisp::io {

struct ReadFailure {
    std::string location; // "line 12", "byte 1024", "accessors[3]"; empty when not applicable
    std::string message;
};

[[noreturn]] inline void fail(std::string location, std::string message)
{
    throw ReadFailure{ std::move(location), std::move(message) };
}

inline std::string lineAt(std::uint64_t line)
{
    return "line " + std::to_string(line);
}
inline std::string byteAt(std::uint64_t offset)
{
    return "byte " + std::to_string(offset);
}

// "1 byte", "3 bytes"
inline std::string plural(std::uint64_t n, const char* one, const char* many)
{
    return std::to_string(n) + " " + (n == 1 ? one : many);
}

} // namespace wisp::io
