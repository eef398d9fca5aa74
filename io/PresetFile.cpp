#include "io/PresetFile.h"

#include "io/JsonErrors.h"
#include "io/MotionJson.h"
#include "io/RegularFile.h"

#include "io/AtomicFile.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

namespace wisp::io {

using nlohmann::json;
using nlohmann::ordered_json;
namespace fs = std::filesystem;

namespace detail {

namespace {

constexpr std::size_t kMaxWarnings = 50;
constexpr std::size_t kMaxQuotedBytes = 40; // of a string value shown in a message
constexpr std::size_t kMaxKeyBytes = 64; // of an unknown key shown in a warning

// Cuts `text` to at most `maxBytes` without splitting a UTF-8 sequence, marking the cut with "…".
std::string shorten(std::string_view text, std::size_t maxBytes)
{
    if (text.size() <= maxBytes)
        return std::string(text);
    std::size_t cut = maxBytes;
    while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80)
        --cut;
    return std::string(text.substr(0, cut)) + "…";
}

// Shortest decimal that reads back as `value` ("0.001", "2147483647"), for ranges in messages.
std::string shortestText(double value)
{
    char buffer[64];
    for (int precision = 1; precision <= 17; ++precision) {
        std::snprintf(buffer, sizeof buffer, "%.*g", precision, value);
        if (std::strtod(buffer, nullptr) == value)
            break;
    }
    return buffer;
}

std::string megabytes(std::size_t bytes)
{
    return megabytesText(bytes);
}

// A short array of plain numbers ([0.16, 0.1, 0.06]) starting at text[open] == '[': its one-line
// form, or empty if the array holds anything else or is long.
std::string oneLineNumberArray(const std::string& text, std::size_t open, std::size_t& close)
{
    constexpr std::size_t kMaxItems = 4;
    std::vector<std::string> items(1);
    for (std::size_t i = open + 1; i < text.size(); ++i) {
        const char c = text[i];
        if (c == ']') {
            close = i;
            if (items.size() > kMaxItems || items.back().empty())
                return {};
            std::string line = "[";
            for (std::size_t k = 0; k < items.size(); ++k)
                line += (k ? ", " : "") + items[k];
            return line + "]";
        }
        if (c == ',')
            items.emplace_back();
        else if (std::strchr("0123456789+-.eE", c))
            items.back() += c;
        else if (c != ' ' && c != '\n')
            return {};
    }
    return {};
}

} // namespace

void Warnings::add(const std::string& path, const std::string& what)
{
    if (m_lines.size() < kMaxWarnings)
        m_lines.push_back(path + ": " + what);
    else
        ++m_unreported;
}

std::vector<std::string> Warnings::take()
{
    if (m_unreported > 0)
        m_lines.push_back("… and " + std::to_string(m_unreported) + " more warnings like these");
    m_unreported = 0;
    return std::move(m_lines);
}

json parseJson(std::string_view text, std::size_t maxBytes, const char* what)
{
    if (text.size() > maxBytes)
        throw Refusal{ "",
            "the text is " + megabytes(text.size()) + "; a " + what + " is at most " + megabytes(maxBytes) };
    if (text.find_first_not_of(" \t\r\n") == std::string_view::npos)
        throw Refusal{ "", "the file is empty" };
    try {
        return json::parse(text.begin(), text.end());
    } catch (const json::exception& e) { // parse_error, and out_of_range for a number that overflows
        const JsonFailure failure = describeJsonFailure(text, e);
        // "last read" quotes the token, which may be megabytes of string: shorten.
        throw Refusal{ failure.place, shorten(failure.message, 200) };
    }
}

int checkFormatAndVersion(const json& root, std::string_view format, const char* kind, int newestVersion,
    std::string_view otherFormat, const char* otherKind)
{
    if (!root.is_object())
        throw Refusal{ "", "expected a JSON object { ... } around the whole file, found " + describe(root) };
    const auto formatIt = root.find("format");
    if (formatIt == root.end())
        throw Refusal{ "format", "missing; the file should start with \"format\": \"" + std::string(format) + "\"" };
    if (formatIt->is_string() && formatIt->get_ref<const std::string&>() == otherFormat)
        throw Refusal{ "format", std::string("this is ") + otherKind + ", not a " + kind };
    if (!formatIt->is_string() || formatIt->get_ref<const std::string&>() != format)
        throw Refusal{ "format", describe(*formatIt) + " is not \"" + std::string(format) + "\"" };
    const auto versionIt = root.find("version");
    if (versionIt == root.end())
        throw Refusal{ "version", "missing" };
    if (!versionIt->is_number() || std::floor(versionIt->get<double>()) != versionIt->get<double>())
        throw Refusal{ "version", describe(*versionIt) + " is not a whole number" };
    const double version = versionIt->get<double>();
    if (version < 1)
        throw Refusal{ "version", describe(*versionIt) + " is not a version (they start at 1)" };
    if (version > newestVersion)
        throw Refusal{ "",
            "version " + describe(*versionIt) + " is newer than this Wisp reads (" + std::to_string(newestVersion)
                + ")" };
    return static_cast<int>(version);
}

std::string describe(const json& value)
{
    const auto errors = json::error_handler_t::replace;
    switch (value.type()) {
    case json::value_t::string: {
        const std::string& text = value.get_ref<const std::string&>();
        if (text.size() <= kMaxQuotedBytes)
            return value.dump(-1, ' ', false, errors);
        std::string quoted = json(shorten(text, kMaxQuotedBytes)).dump(-1, ' ', false, errors);
        return quoted;
    }
    case json::value_t::array:
        return "a list";
    case json::value_t::object:
        return "an object";
    default:
        return value.dump(-1, ' ', false, errors); // numbers as written (3.0 stays 3.0), true, null
    }
}

std::string childPath(const std::string& path, std::string_view key)
{
    const std::string shown = shorten(key, kMaxKeyBytes);
    return path.empty() ? shown : path + "." + shown;
}

const json& requireObject(const json& value, const std::string& path)
{
    if (!value.is_object())
        throw Refusal{ path, "expected an object { ... }, found " + describe(value) };
    return value;
}

std::string readText(const json& value, const std::string& path, std::size_t maxBytes)
{
    if (!value.is_string())
        throw Refusal{ path, describe(value) + " is not text (text goes in double quotes)" };
    const std::string& text = value.get_ref<const std::string&>();
    if (text.size() > maxBytes)
        throw Refusal{ path,
            "the text is " + std::to_string(text.size()) + " bytes long; at most " + std::to_string(maxBytes)
                + " are allowed" };
    return text;
}

double readFiniteNumber(const json& value, const std::string& path)
{
    if (!value.is_number())
        throw Refusal{ path, describe(value) + " is not a number" };
    const double number = value.get<double>();
    if (!std::isfinite(number))
        throw Refusal{ path, describe(value) + " is not a finite number" };
    return number;
}

bool readBool(const json& value, const std::string& path)
{
    if (!value.is_boolean())
        throw Refusal{ path, describe(value) + " is not true or false" };
    return value.get<bool>();
}

void readParameter(ParameterValues& into, const ParameterInfo& info, const json& value, const std::string& path)
{
    double number = 0.0;
    if (info.kind == ParamKind::Toggle) {
        // true/false is what Wisp writes; 1 and 0 are what version 1 and the CLI use.
        if (value.is_boolean())
            number = value.get<bool>() ? 1.0 : 0.0;
        else if (value.is_number() && (value.get<double>() == 0.0 || value.get<double>() == 1.0))
            number = value.get<double>();
        else
            throw Refusal{ path, describe(value) + " is not true or false" };
    } else {
        number = readFiniteNumber(value, path);
        if (info.kind == ParamKind::Integer && std::floor(number) != number)
            throw Refusal{ path, describe(value) + " is not a whole number" };
        if (!isWithinRange(info, number)) // as floats for real parameters: both ends as written are inside
            throw Refusal{ path,
                describe(value) + " is outside " + shortestText(info.minimum) + ".." + shortestText(info.maximum) };
    }
    if (std::string error = into.set(info.id, number); !error.empty())
        throw Refusal{ path, error }; // unreachable while the checks above match the registry's
}

glm::vec3 readColour(const json& value, const std::string& path)
{
    const bool ok = value.is_array() && value.size() == 3 && std::all_of(value.begin(), value.end(), [](const json& c) {
        return c.is_number() && c.get<double>() >= 0.0 && c.get<double>() <= 1.0;
    });
    if (!ok)
        throw Refusal{ path, "expected 3 numbers 0..1" };
    return { static_cast<float>(value[0].get<double>()), static_cast<float>(value[1].get<double>()),
        static_cast<float>(value[2].get<double>()) };
}

double shortestDoubleForFloat(float value)
{
    if (!std::isfinite(value))
        return value;
    char buffer[32];
    for (int precision = 1; precision <= 9; ++precision) { // 9 significant digits always suffice for a float
        std::snprintf(buffer, sizeof buffer, "%.*g", precision, static_cast<double>(value));
        const double candidate = std::strtod(buffer, nullptr);
        if (std::bit_cast<std::uint32_t>(static_cast<float>(candidate)) == std::bit_cast<std::uint32_t>(value))
            return candidate;
    }
    return value;
}

void writeParameter(ordered_json& object, const ParameterInfo& info, double value)
{
    const std::string key(info.key);
    switch (info.kind) {
    case ParamKind::Integer:
        object[key] = static_cast<std::int64_t>(std::llround(value));
        break;
    case ParamKind::Toggle:
        object[key] = value != 0.0;
        break;
    case ParamKind::Real:
        object[key] = value; // nlohmann prints the shortest text that reads back as the same double
        break;
    }
}

ordered_json vec3ToJson(const glm::vec3& value)
{
    return ordered_json::array(
        { shortestDoubleForFloat(value.x), shortestDoubleForFloat(value.y), shortestDoubleForFloat(value.z) });
}

std::string dumpPretty(const ordered_json& root)
{
    const std::string text = root.dump(2, ' ', false, json::error_handler_t::replace);
    std::string out;
    out.reserve(text.size());
    bool inString = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (inString) {
            out += c;
            if (c == '\\' && i + 1 < text.size())
                out += text[++i];
            else if (c == '"')
                inString = false;
            continue;
        }
        if (c == '"')
            inString = true;
        if (c == '[') {
            std::size_t close = 0;
            if (std::string line = oneLineNumberArray(text, i, close); !line.empty()) {
                out += line;
                i = close;
                continue;
            }
        }
        out += c;
    }
    return out + "\n";
}

} // namespace detail

namespace {

using namespace detail;

const std::string kDefaultRegionName = "Scalp"; // as the editor names its first region

// Reads a region's wisp keys from `object` (its "wisp", or the region itself); `seen` lists the
// keys already read for this region so that one given twice is refused. Keys that are not wisp
// parameters are warned about, except `ownKeys` (the region's own, when reading the region).
void readWispKeys(const json& object, const std::string& path, std::initializer_list<std::string_view> ownKeys,
    RegionLook& look, std::map<std::string, std::string>& seen, Warnings& warnings)
{
    for (const auto& [key, value] : object.items()) {
        if (std::find(ownKeys.begin(), ownKeys.end(), key) != ownKeys.end())
            continue;
        const std::string keyPath = childPath(path, key);
        const ParameterInfo* info = findParameter(key);
        if (!info) {
            warnings.add(keyPath, "unknown key, ignored");
        } else if (info->group != ParamGroup::Wisp) {
            warnings.add(keyPath, "a global parameter, which belongs in \"parameters\"; ignored here");
        } else {
            if (const auto before = seen.find(key); before != seen.end())
                throw Refusal{ keyPath, "given twice, here and at " + before->second };
            seen.emplace(key, keyPath);
            readParameter(look.wisp, *info, value, keyPath);
        }
    }
}

RegionLook readRegionLook(const json& value, std::size_t index, Warnings& warnings)
{
    const std::string path = "regions[" + std::to_string(index) + "]";
    requireObject(value, path);
    RegionLook look;
    look.name = "Region " + std::to_string(index + 1);
    if (const auto it = value.find("name"); it != value.end())
        look.name = readText(*it, childPath(path, "name"), kMaxNameBytes);
    if (const auto it = value.find("root_colour"); it != value.end())
        look.rootColour = readColour(*it, childPath(path, "root_colour"));
    if (const auto it = value.find("tip_colour"); it != value.end())
        look.tipColour = readColour(*it, childPath(path, "tip_colour"));
    std::map<std::string, std::string> seen;
    if (const auto it = value.find("wisp"); it != value.end()) {
        const std::string wispPath = childPath(path, "wisp");
        readWispKeys(requireObject(*it, wispPath), wispPath, {}, look, seen, warnings);
    }
    readWispKeys(value, path, { "name", "wisp", "root_colour", "tip_colour" }, look, seen, warnings);
    return look;
}

Preset readPresetJson(const json& root, const std::string& nameForMessages, Warnings& warnings)
{
    const int version
        = checkFormatAndVersion(root, "wisp-preset", "preset", kPresetVersion, "wisp-project", "a Wisp project");
    Preset preset;
    preset.name = fs::path(nameForMessages).stem().string();
    if (const auto it = root.find("name"); it != root.end())
        preset.name = readText(*it, "name", kMaxNameBytes);
    if (const auto it = root.find("description"); it != root.end())
        preset.description = readText(*it, "description", kMaxDescriptionBytes);

    RegionLook flatRegion; // version 1: the wisp keys of the flat "parameters"
    flatRegion.name = kDefaultRegionName;
    if (const auto it = root.find("parameters"); it != root.end()) {
        requireObject(*it, "parameters");
        for (const auto& [key, value] : it->items()) {
            const std::string path = childPath("parameters", key);
            const ParameterInfo* info = findParameter(key);
            if (!info)
                warnings.add(path, "unknown key, ignored");
            else if (info->group != ParamGroup::Wisp)
                readParameter(preset.parameters, *info, value, path);
            else if (version == 1)
                readParameter(flatRegion.wisp, *info, value, path);
            else
                warnings.add(path, "a region's parameter, which belongs in a region's \"wisp\"; ignored here");
        }
    }

    if (version == 1) {
        preset.regions.push_back(std::move(flatRegion));
    } else if (const auto it = root.find("regions"); it != root.end()) {
        if (!it->is_array())
            throw Refusal{ "regions", "expected a list [ ... ] of regions, found " + describe(*it) };
        if (it->size() > kMaxRegions)
            throw Refusal{ "regions",
                std::to_string(it->size()) + " regions; at most " + std::to_string(kMaxRegions) + " are allowed" };
        for (std::size_t i = 0; i < it->size(); ++i)
            preset.regions.push_back(readRegionLook((*it)[i], i, warnings));
    }

    if (const auto it = root.find("motion"); it != root.end()) {
        const HeadMotion motion = readMotion(*it, "motion", warnings);
        if (!motion.keys().empty())
            warnings.add("motion.keys", "a preset keeps a procedural motion only; keys ignored");
        preset.motion = motion.procedural();
    }

    for (const auto& [key, value] : root.items()) {
        static const std::set<std::string> known
            = { "format", "version", "name", "description", "parameters", "regions", "motion" };
        if (!known.contains(key) || (key == "regions" && version == 1))
            warnings.add(childPath("", key), "unknown key, ignored");
    }
    return preset;
}

} // namespace

Result<PresetReadResult> readPreset(const std::string& path)
{
    std::string text;
    try {
        text = readRegularFileOrFail(path, { kMaxPresetBytes, "preset", true });
    } catch (const Refusal& refusal) {
        return IoError{ path, refusal.location, refusal.message };
    }
    return parsePreset(text, path);
}

Result<PresetReadResult> parsePreset(std::string_view text, const std::string& nameForMessages)
{
    try {
        const json root = parseJson(text, kMaxPresetBytes, "preset");
        Warnings warnings;
        Preset preset = readPresetJson(root, nameForMessages, warnings);
        return PresetReadResult{ std::move(preset), warnings.take() };
    } catch (const Refusal& refusal) {
        return IoError{ nameForMessages, refusal.location, refusal.message };
    } catch (const json::exception& e) { // a check above missed a case: still an error, not a crash
        return IoError{ nameForMessages, "", withoutJsonPrefix(e.what()) };
    } catch (const std::bad_alloc&) {
        return IoError{ nameForMessages, "", "not enough memory to read the preset" };
    }
}

std::string presetToJson(const Preset& preset)
{
    ordered_json root;
    root["format"] = "wisp-preset";
    root["version"] = kPresetVersion;
    root["name"] = preset.name;
    root["description"] = preset.description;
    ordered_json parameters = ordered_json::object();
    for (const ParameterInfo& info : allParameters())
        if (info.group != ParamGroup::Wisp)
            writeParameter(parameters, info, preset.parameters.get(info.id));
    root["parameters"] = std::move(parameters);
    ordered_json regions = ordered_json::array();
    for (const RegionLook& look : preset.regions) {
        ordered_json region;
        region["name"] = look.name;
        ordered_json wisp = ordered_json::object();
        for (const ParameterInfo& info : allParameters())
            if (info.group == ParamGroup::Wisp)
                writeParameter(wisp, info, look.wisp.get(info.id));
        region["wisp"] = std::move(wisp);
        region["root_colour"] = vec3ToJson(look.rootColour);
        region["tip_colour"] = vec3ToJson(look.tipColour);
        regions.push_back(std::move(region));
    }
    root["regions"] = std::move(regions);
    if (preset.motion.kind != MotionKind::None) {
        HeadMotion motion;
        motion.setProcedural(preset.motion);
        root["motion"] = motionToJson(motion);
    }
    return dumpPretty(root);
}

Result<void> writePreset(const std::string& path, const Preset& preset)
{
    const std::string text = presetToJson(preset);
    return writeFileAtomically(path, [&](std::ostream& out) { out << text; });
}

} // namespace wisp::io
