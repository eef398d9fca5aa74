#include "io/ParameterText.h"
#include "io/RegularFile.h"

#include <cerrno>
#include <cstdlib>
#include <sstream>

namespace wisp::io {

namespace {
std::string trim(const std::string& s)
{
    const auto begin = s.find_first_not_of(" \t\r");
    if (begin == std::string::npos)
        return {};
    const auto end = s.find_last_not_of(" \t\r");
    return s.substr(begin, end - begin + 1);
}
} // namespace

Result<ParameterFile> readParameterText(const std::string& path)
{
    Result<std::string> text = readRegularFile(path, { kMaxTextFileBytes, "parameter", true });
    if (!text)
        return text.error();
    std::istringstream in(std::move(text).value());
    ParameterFile file;
    std::string line;
    for (std::size_t number = 1; std::getline(in, line); ++number) {
        const std::string where = "line " + std::to_string(number);
        if (const auto hash = line.find('#'); hash != std::string::npos)
            line.resize(hash);
        line = trim(line);
        if (line.empty())
            continue;
        const auto equals = line.find('=');
        if (equals == std::string::npos)
            return IoError{ path, where, "expected 'key = value', got '" + line + "'" };
        const std::string key = trim(line.substr(0, equals));
        const std::string text = trim(line.substr(equals + 1));
        const ParameterInfo* info = findParameter(key);
        if (!info)
            return IoError{ path, where, "unknown parameter '" + key + "'" };
        char* end = nullptr;
        errno = 0;
        const double value = std::strtod(text.c_str(), &end);
        if (text.empty() || end != text.c_str() + text.size())
            return IoError{ path, where, key + ": '" + text + "' is not a number" };
        if (std::string error = checkParameterValue(info->id, value); !error.empty())
            return IoError{ path, where, error };
        file.values.emplace_back(info->id, value);
    }
    return file;
}

} // namespace wisp::io
