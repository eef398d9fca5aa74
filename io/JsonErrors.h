#pragma once
// nlohmann's exceptions in an artist's words. Its raw text ("[json.exception.out_of_range.406]
// number overflow parsing '1e999'") named no place and leaked into messages; every JSON reader
// (presets, projects, glTF) turns its parse failures into a place and a message here.

#include <nlohmann/json.hpp>

#include <string>
#include <string_view>

namespace wisp::io {

struct JsonFailure {
    std::string place;    // "line 3, column 30"; empty when nlohmann gives no place and none is found
    std::string message;  // without nlohmann's "[json.exception...]" prefix
};

// A failure thrown by nlohmann::json::parse over `text`.
JsonFailure describeJsonFailure(std::string_view text, const nlohmann::json::exception& error);

// nlohmann's text without its "[json.exception.type.id] " prefix (and "parse error at ...: ").
std::string withoutJsonPrefix(const std::string& what);

// "line L, column C" of byte `offset` (0-based) of `text`.
std::string lineAndColumn(std::string_view text, std::size_t offset);

}  // namespace wisp::io
