#include "io/GltfSchema.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <string_view>
#include <system_error>
#include <vector>

namespace wisp::io {

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

struct Problem {
    GltfSchemaProblem what;
};

// Unknown keys that are no near miss: warned about, as Khronos' validator does (real exporters
// leave glTF 1.0 keys behind, e.g. accessor byteStride in the Box sample).
thread_local std::vector<std::string>* t_warnings = nullptr;

[[noreturn]] void refuse(std::string keyPath, std::string message)
{
    throw Problem{ { std::move(keyPath), std::move(message) } };
}

enum class Kind { Integer, Number, Boolean, String, Object, Array };

const char* kindName(Kind kind)
{
    switch (kind) {
    case Kind::Integer:
        return "a whole number";
    case Kind::Number:
        return "a number";
    case Kind::Boolean:
        return "true or false";
    case Kind::String:
        return "a string";
    case Kind::Object:
        return "an object";
    case Kind::Array:
        return "a list";
    }
    return "?";
}

std::string jsonTypeName(const Json& value)
{
    if (value.is_boolean())
        return value.get<bool>() ? "true" : "false";
    if (value.is_null())
        return "null";
    if (value.is_string())
        return "a string";
    if (value.is_object())
        return "an object";
    if (value.is_array())
        return "a list";
    if (value.is_number_integer())
        return std::to_string(value.get<long long>());
    return value.dump();
}

// JSON has one number type: 4.0 is a whole number, as the Khronos validator takes it.
bool isInteger(const Json& value)
{
    if (value.is_number_integer())
        return true;
    if (!value.is_number_float())
        return false;
    const double d = value.get<double>();
    return std::isfinite(d) && d == std::floor(d) && std::fabs(d) < 9.007199254740992e15;
}

double numberOf(const Json& value)
{
    return value.get<double>();
}

bool hasKind(const Json& value, Kind kind)
{
    switch (kind) {
    case Kind::Integer:
        return isInteger(value);
    case Kind::Number:
        return value.is_number();
    case Kind::Boolean:
        return value.is_boolean();
    case Kind::String:
        return value.is_string();
    case Kind::Object:
        return value.is_object();
    case Kind::Array:
        return value.is_array();
    }
    return false;
}

std::size_t editDistance(std::string_view a, std::string_view b)
{
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j)
        row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t above = row[j];
            row[j] = std::min({ row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1) });
            diagonal = above;
        }
    }
    return row[b.size()];
}

struct Field {
    const char* key;
    Kind kind;
    bool required = false;
    double minimum = -INFINITY; // for Integer and Number
    double maximum = INFINITY;
};

std::string child(const std::string& path, std::string_view key)
{
    return path.empty() ? std::string(key) : path + "." + std::string(key);
}

std::string element(const std::string& path, std::size_t i)
{
    return path + "[" + std::to_string(i) + "]";
}

std::string rangeText(const Field& field)
{
    auto number = [](double d) {
        char text[32];
        std::snprintf(text, sizeof text, "%.15g", d);
        return std::string(text);
    };
    if (std::isfinite(field.minimum) && std::isfinite(field.maximum))
        return number(field.minimum) + ".." + number(field.maximum);
    if (std::isfinite(field.minimum))
        return "at least " + number(field.minimum);
    return "at most " + number(field.maximum);
}

// Checks `object` (at `path`) against `fields`; `name`, `extensions` and `extras` are always allowed.
void checkObject(const Json& object, const std::string& path, std::initializer_list<Field> fields)
{
    if (!object.is_object())
        refuse(path, "must be an object, not " + jsonTypeName(object));
    for (const auto& [key, value] : object.items()) {
        if (key == "extensions" || key == "extras") {
            if (key == "extensions" && !value.is_object())
                refuse(child(path, key), "must be an object, not " + jsonTypeName(value));
            continue;
        }
        if (key == "name") {
            if (!value.is_string())
                refuse(child(path, key), "must be a string, not " + jsonTypeName(value));
            continue;
        }
        const Field* field = nullptr;
        for (const Field& f : fields)
            if (key == f.key)
                field = &f;
        if (!field) {
            // A near miss of a key the object lacks is a typo that changes what the file means
            // (`byteOffet`: the view would start at byte 0): refused. Anything else is ignored
            // with a warning.
            std::string nearest;
            std::size_t best = 3;
            for (const Field& f : fields)
                if (const std::size_t d = editDistance(key, f.key); d < best && !object.contains(f.key)) {
                    best = d;
                    nearest = f.key;
                }
            if (!nearest.empty())
                refuse(child(path, key),
                    "unknown key (did you mean '" + nearest
                        + "'?); glTF readers ignore it, so the file would not mean what it says");
            if (t_warnings != nullptr)
                t_warnings->push_back(child(path, key) + ": unknown key, ignored");
            continue;
        }
        if (!hasKind(value, field->kind))
            refuse(child(path, key), std::string("must be ") + kindName(field->kind) + ", not " + jsonTypeName(value));
        if ((field->kind == Kind::Integer || field->kind == Kind::Number)
            && !(numberOf(value) >= field->minimum && numberOf(value) <= field->maximum))
            refuse(child(path, key), jsonTypeName(value) + " is outside " + rangeText(*field));
    }
    for (const Field& f : fields)
        if (f.required && !object.contains(f.key))
            refuse(child(path, f.key), "missing; the glTF schema requires it");
}

// A list at `path` (`required` or not) whose elements each pass `each`.
template <typename Each>
void checkList(const Json& parent, const std::string& parentPath, const char* key, bool required, Each each)
{
    const auto it = parent.find(key);
    const std::string path = child(parentPath, key);
    if (it == parent.end()) {
        if (required)
            refuse(path, "missing; the glTF schema requires it");
        return;
    }
    if (!it->is_array())
        refuse(path, "must be a list, not " + jsonTypeName(*it));
    for (std::size_t i = 0; i < it->size(); ++i)
        each((*it)[i], element(path, i));
}

void checkNumberList(const Json& object, const std::string& path, const char* key, std::size_t exactSize, Kind kind)
{
    const auto it = object.find(key);
    if (it == object.end())
        return;
    const std::string at = child(path, key);
    if (exactSize != 0 && it->size() != exactSize)
        refuse(at,
            std::string(key) + " has " + std::to_string(it->size()) + (it->size() == 1 ? " number" : " numbers")
                + "; it needs " + std::to_string(exactSize));
    for (std::size_t i = 0; i < it->size(); ++i) {
        const Json& v = (*it)[i];
        if (!hasKind(v, kind) || (kind == Kind::Number && !std::isfinite(numberOf(v)))
            || (kind == Kind::Integer && numberOf(v) < 0))
            refuse(element(at, i),
                std::string("must be ") + (kind == Kind::Integer ? "an index" : "a finite number") + ", not "
                    + jsonTypeName(v));
    }
}

constexpr double kMaxIndex = 4294967295.0;

} // namespace

std::string gltfUriDecoded(const std::string& uri)
{
    std::string out;
    for (std::size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1]))
            && std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
            out += static_cast<char>(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

namespace {

void checkBufferUri(const std::string& uri, const std::string& path, const fs::path& folder)
{
    if (uri.rfind("data:", 0) == 0)
        return;
    const std::string decoded = gltfUriDecoded(uri);
    const std::string quoted = "'" + (uri.size() > 120 ? uri.substr(0, 120) + "..." : uri) + "'";
    if (decoded.find('\0') != std::string::npos)
        refuse(path, quoted + " holds a NUL character");
    if (const std::size_t colon = decoded.find(':'); colon != std::string::npos && decoded.find('/') > colon)
        refuse(path, quoted + " is a URL; Wisp reads buffers only from files beside the glTF file");
    if (!decoded.empty() && (decoded.front() == '/' || decoded.front() == '\\'))
        refuse(path, quoted + " is an absolute path; a glTF file may read only files in its own folder");
    if (folder.empty())
        refuse(path, quoted + " names an external file, but this glTF was not read from a folder");
    if (!regularFileInside(folder / decoded, folder)) {
        std::error_code ec;
        const fs::path resolved = fs::weakly_canonical(folder / decoded, ec);
        const fs::path base = fs::canonical(folder, ec);
        const fs::path relative = resolved.lexically_relative(base);
        if (relative.empty() || *relative.begin() == "..")
            refuse(path,
                quoted
                    + " lies outside the glTF file's folder; a glTF file shared between artists may read "
                      "only files in its own folder");
        if (!fs::exists(resolved, ec))
            refuse(path, quoted + " does not exist in the glTF file's folder");
        refuse(path, quoted + " is not a regular file");
    }
}

void checkAll(const Json& root, const fs::path& folder)
{
    static const char* const topLevel[] = { "asset", "accessors", "animations", "buffers", "bufferViews", "cameras",
        "extensions", "extensionsUsed", "extensionsRequired", "extras", "images", "materials", "meshes", "nodes",
        "samplers", "scene", "scenes", "skins", "textures" };
    for (const auto& [key, value] : root.items()) {
        (void)value;
        if (std::find_if(std::begin(topLevel), std::end(topLevel), [&name = key](const char* k) { return name == k; })
            != std::end(topLevel))
            continue;
        std::string nearest;
        std::size_t best = 3;
        for (const char* k : topLevel)
            if (const std::size_t d = editDistance(key, k); d < best && !root.contains(k)) {
                best = d;
                nearest = k;
            }
        if (!nearest.empty())
            refuse(key,
                "unknown top-level key (did you mean '" + nearest
                    + "'?); glTF readers ignore it, so the file would not mean what it says");
        if (t_warnings != nullptr)
            t_warnings->push_back(key + ": unknown top-level key, ignored");
    }
    checkObject(root.at("asset"), "asset",
        { { "version", Kind::String, true }, { "minVersion", Kind::String }, { "generator", Kind::String },
            { "copyright", Kind::String } });
    checkList(root, "", "buffers", false, [&](const Json& b, const std::string& path) {
        checkObject(b, path, { { "uri", Kind::String }, { "byteLength", Kind::Integer, true, 1, INFINITY } });
        if (const auto uri = b.find("uri"); uri != b.end())
            checkBufferUri(uri->get<std::string>(), child(path, "uri"), folder);
    });
    checkList(root, "", "bufferViews", false, [](const Json& v, const std::string& path) {
        checkObject(v, path,
            { { "buffer", Kind::Integer, true, 0, kMaxIndex }, { "byteOffset", Kind::Integer, false, 0, INFINITY },
                { "byteLength", Kind::Integer, true, 1, INFINITY }, { "byteStride", Kind::Integer, false, 4, 252 },
                { "target", Kind::Integer, false, 0, 65535 } });
    });
    checkList(root, "", "accessors", false, [](const Json& a, const std::string& path) {
        checkObject(a, path,
            { { "bufferView", Kind::Integer, false, 0, kMaxIndex }, { "byteOffset", Kind::Integer, false, 0, INFINITY },
                { "componentType", Kind::Integer, true, 0, 65535 }, { "normalized", Kind::Boolean },
                { "count", Kind::Integer, true, 1, INFINITY }, { "type", Kind::String, true }, { "max", Kind::Array },
                { "min", Kind::Array }, { "sparse", Kind::Object } });
        checkNumberList(a, path, "max", 0, Kind::Number);
        checkNumberList(a, path, "min", 0, Kind::Number);
        if (const auto sparse = a.find("sparse"); sparse != a.end()) {
            const std::string at = child(path, "sparse");
            checkObject(*sparse, at,
                { { "count", Kind::Integer, true, 1, INFINITY }, { "indices", Kind::Object, true },
                    { "values", Kind::Object, true } });
            checkObject(sparse->at("indices"), child(at, "indices"),
                { { "bufferView", Kind::Integer, true, 0, kMaxIndex },
                    { "byteOffset", Kind::Integer, false, 0, INFINITY },
                    { "componentType", Kind::Integer, true, 0, 65535 } });
            checkObject(sparse->at("values"), child(at, "values"),
                { { "bufferView", Kind::Integer, true, 0, kMaxIndex },
                    { "byteOffset", Kind::Integer, false, 0, INFINITY } });
        }
    });
    checkList(root, "", "meshes", false, [](const Json& m, const std::string& path) {
        checkObject(m, path, { { "primitives", Kind::Array, true }, { "weights", Kind::Array } });
        checkNumberList(m, path, "weights", 0, Kind::Number);
        checkList(m, path, "primitives", true, [](const Json& p, const std::string& at) {
            checkObject(p, at,
                { { "attributes", Kind::Object, true }, { "indices", Kind::Integer, false, 0, kMaxIndex },
                    { "material", Kind::Integer, false, 0, kMaxIndex }, { "mode", Kind::Integer, false, 0, 6 },
                    { "targets", Kind::Array } });
            for (const auto& [name, index] : p.at("attributes").items())
                if (!isInteger(index) || numberOf(index) < 0)
                    refuse(
                        child(child(at, "attributes"), name), "must be an accessor index, not " + jsonTypeName(index));
        });
    });
    checkList(root, "", "nodes", false, [](const Json& n, const std::string& path) {
        checkObject(n, path,
            { { "camera", Kind::Integer, false, 0, kMaxIndex }, { "children", Kind::Array },
                { "skin", Kind::Integer, false, 0, kMaxIndex }, { "matrix", Kind::Array },
                { "mesh", Kind::Integer, false, 0, kMaxIndex }, { "rotation", Kind::Array }, { "scale", Kind::Array },
                { "translation", Kind::Array }, { "weights", Kind::Array } });
        checkNumberList(n, path, "children", 0, Kind::Integer);
        checkNumberList(n, path, "matrix", 16, Kind::Number);
        checkNumberList(n, path, "rotation", 4, Kind::Number);
        checkNumberList(n, path, "scale", 3, Kind::Number);
        checkNumberList(n, path, "translation", 3, Kind::Number);
        checkNumberList(n, path, "weights", 0, Kind::Number);
    });
    checkList(root, "", "scenes", false, [](const Json& s, const std::string& path) {
        checkObject(s, path, { { "nodes", Kind::Array } });
        checkNumberList(s, path, "nodes", 0, Kind::Integer);
    });
    if (const auto scene = root.find("scene"); scene != root.end() && !(isInteger(*scene) && numberOf(*scene) >= 0))
        refuse("scene", "must be a scene index, not " + jsonTypeName(*scene));
}

} // namespace

bool regularFileInside(const fs::path& path, const fs::path& folder)
{
    std::error_code ec;
    const fs::path base = fs::canonical(folder, ec);
    if (ec)
        return false;
    const fs::path resolved = fs::canonical(path, ec); // follows every symlink, so one leading out is out
    if (ec)
        return false;
    const fs::path relative = resolved.lexically_relative(base);
    if (relative.empty() || *relative.begin() == ".." || relative == ".")
        return false;
    return fs::is_regular_file(resolved, ec);
}

std::optional<GltfSchemaProblem> checkGltfSchema(
    const Json& root, const fs::path& folder, std::vector<std::string>& warnings)
{
    t_warnings = &warnings;
    std::optional<GltfSchemaProblem> result;
    try {
        checkAll(root, folder);
    } catch (const Problem& problem) {
        result = problem.what;
    }
    t_warnings = nullptr;
    return result;
}

} // namespace wisp::io
