#pragma once
// The tokenizer the text mesh formats (OBJ, OFF, ASCII PLY, ASCII STL) share: lines numbered from
// 1, whitespace-separated tokens, and numbers parsed with std::from_chars, which ignores the locale
// (a Qt app may switch LC_NUMERIC to one with a decimal comma) and says how much of a token it used.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace wisp::io::mesh {

// Parses the whole token; false if it is not a number. Overflow gives +-inf and underflow 0, so
// the caller sees the value the file meant and can refuse non-finite values with context.
bool parseDouble(std::string_view token, double& value);
bool parseInteger(std::string_view token, std::int64_t& value);

inline bool isSpace(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}

void splitTokens(std::string_view line, std::vector<std::string_view>& tokens);

// A token for a message: at most 40 characters, unprintable ones as '?', in quotes (a binary
// file read as text would otherwise swamp the message).
std::string quoted(std::string_view text);

// Walks a text file line by line, numbering lines from 1 and dropping a trailing '\r'.
class LineWalker {
public:
    explicit LineWalker(std::string_view text)
        : m_text(text)
    {
    }

    bool next(std::string_view& line);
    std::size_t lineNumber() const { return m_line; } // of the line next() returned last
    std::size_t offset() const { return m_pos; } // of the line next() returns next

private:
    std::string_view m_text;
    std::size_t m_pos = 0;
    std::size_t m_nextLine = 1;
    std::size_t m_line = 0;
};

} // namespace wisp::io::mesh
