#pragma once
// nlohmann's exceptions in an artist's words. Its raw text ("[json.exception.out_of_range.406]
// number overflow parsing '1e999'") named no place and leaked into messages; every JSON reader
// (presets, projects, glTF) turns its parse failures into a place and a message here.

#include <nlohmann/json.hpp>

#include <string>
#include <string_view>

namespace wisp::io {

struct JsonFailure {
    std::string place; // "line 3, column 30"; empty when nlohmann gives no place and none is found
    std::string message; // without nlohmann's "[json.exception...]" prefix
};

// A failure thrown by nlohmann::json::parse over `text`.
JsonFailure describeJsonFailure(std::string_view text, const nlohmann::json::exception& error);

// nlohmann's text without its "[json.exception.type.id] " prefix (and "parse error at ...: ").
std::string withoutJsonPrefix(const std::string& what);

// The first offset of `text` outside JSON strings (string quotes included in the string) at
// which `found(offset, byte)` is true, or npos. Shared by the readers that scan JSON text before
// or after nlohmann: the glTF nesting guard and the overflowing-number search.
template <class Found> std::size_t findOutsideJsonStrings(std::string_view text, Found found)
{
    bool inString = false, escaped = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (inString) {
            if (escaped)
                escaped = false;
            else if (c == '\\')
                escaped = true;
            else if (c == '"')
                inString = false;
        } else if (c == '"') {
            inString = true;
        } else if (found(i, c)) {
            return i;
        }
    }
    return std::string_view::npos;
}

// "line L, column C" of byte `offset` (0-based) of `text`.
std::string lineAndColumn(std::string_view text, std::size_t offset);

} // namespace wisp::io
