#include "io/JsonErrors.h"

#include <algorithm>

namespace wisp::io {

std::string lineAndColumn(std::string_view text, std::size_t offset)
{
    offset = std::min(offset, text.size());
    const std::string_view before = text.substr(0, offset);
    const std::size_t line = 1 + static_cast<std::size_t>(std::count(before.begin(), before.end(), '\n'));
    const std::size_t newline = before.rfind('\n');
    const std::size_t lineStart = newline == std::string_view::npos ? 0 : newline + 1;
    return "line " + std::to_string(line) + ", column " + std::to_string(offset - lineStart + 1);
}

std::string withoutJsonPrefix(const std::string& what)
{
    std::string text = what;
    if (const std::size_t close = text.find("] "); !text.empty() && text.front() == '[' && close != std::string::npos)
        text.erase(0, close + 2);
    if (text.rfind("parse error", 0) == 0)
        if (const std::size_t colon = text.find(": "); colon != std::string::npos)
            text.erase(0, colon + 2);
    return text;
}

JsonFailure describeJsonFailure(std::string_view text, const nlohmann::json::exception& error)
{
    JsonFailure failure;
    failure.message = withoutJsonPrefix(error.what());
    if (const auto* parse = dynamic_cast<const nlohmann::json::parse_error*>(&error)) {
        // nlohmann's byte is 1-based and may point one past the end.
        failure.place = lineAndColumn(text, parse->byte > 0 ? parse->byte - 1 : 0);
        return failure;
    }
    // out_of_range.406, "number overflow parsing '1e999'": nlohmann gives no place, so find the
    // number in the text (its first occurrence outside a string).
    const std::string marker = "number overflow parsing '";
    if (const std::size_t at = failure.message.find(marker); at != std::string::npos) {
        const std::size_t start = at + marker.size();
        const std::string number = failure.message.substr(start, failure.message.rfind('\'') - start);
        failure.message = "the number " + number + " is too large to hold (it overflows a double)";
        const std::size_t where = findOutsideJsonStrings(
            text, [&](std::size_t i, char) { return text.substr(i, number.size()) == number; });
        if (where != std::string_view::npos)
            failure.place = lineAndColumn(text, where);
    }
    return failure;
}

} // namespace wisp::io
