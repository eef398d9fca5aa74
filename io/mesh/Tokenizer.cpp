#include "io/mesh/Tokenizer.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <system_error>

namespace wisp::io::mesh {

bool parseDouble(std::string_view token, double& value)
{
    if (!token.empty() && token.front() == '+')
        token.remove_prefix(1);
    if (token.empty())
        return false;
    const char* end = token.data() + token.size();
    const auto [ptr, ec] = std::from_chars(token.data(), end, value);
    if (ptr != end)
        return false;
    if (ec == std::errc::result_out_of_range) {
        const std::size_t e = token.find_first_of("eE");
        const bool tiny = e != std::string_view::npos && e + 1 < token.size() && token[e + 1] == '-';
        const bool negative = token.front() == '-';
        value = tiny ? 0.0 : (negative ? -HUGE_VAL : HUGE_VAL);
        return true;
    }
    return ec == std::errc();
}

bool parseInteger(std::string_view token, std::int64_t& value)
{
    if (!token.empty() && token.front() == '+')
        token.remove_prefix(1);
    if (token.empty())
        return false;
    const char* end = token.data() + token.size();
    const auto [ptr, ec] = std::from_chars(token.data(), end, value);
    return ec == std::errc() && ptr == end;
}

void splitTokens(std::string_view line, std::vector<std::string_view>& tokens)
{
    tokens.clear();
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && isSpace(line[i]))
            ++i;
        const std::size_t start = i;
        while (i < line.size() && !isSpace(line[i]))
            ++i;
        if (i > start)
            tokens.push_back(line.substr(start, i - start));
    }
}

std::string quoted(std::string_view text)
{
    constexpr std::size_t maxChars = 40;
    std::string s(text.substr(0, maxChars));
    for (char& c : s)
        if (!std::isprint(static_cast<unsigned char>(c)))
            c = '?';
    return "'" + s + (text.size() > maxChars ? "...'" : "'");
}

bool LineWalker::next(std::string_view& line)
{
    if (m_pos >= m_text.size())
        return false;
    std::size_t end = m_text.find('\n', m_pos);
    const std::size_t after = end == std::string_view::npos ? m_text.size() : end + 1;
    if (end == std::string_view::npos)
        end = m_text.size();
    line = m_text.substr(m_pos, end - m_pos);
    if (!line.empty() && line.back() == '\r')
        line.remove_suffix(1);
    m_pos = after;
    m_line = m_nextLine++;
    return true;
}

} // namespace wisp::io::mesh
