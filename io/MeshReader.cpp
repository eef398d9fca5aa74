#include "io/MeshReader.h"

#include "io/GltfReader.h"
#include "io/RegularFile.h"

#include <OpenMesh/Core/IO/Options.hh>
#include <OpenMesh/Core/IO/importer/BaseImporter.hh>
#include <OpenMesh/Core/IO/reader/OBJReader.hh>
#include <OpenMesh/Core/IO/reader/STLReader.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>
#include <system_error>

namespace wisp::io {

namespace {

// ---------------------------------------------------------------------------------------------
// Failure inside this file. Thrown by the parsers (and through OpenMesh's readers, from our
// importer) and turned into an IoError by readMesh, so every parser reads top to bottom
// instead of threading error codes through each number it reads.
struct ReadFailure {
    std::string location;
    std::string message;
};

[[noreturn]] void fail(std::string location, std::string message)
{
    throw ReadFailure{std::move(location), std::move(message)};
}

std::string lineAt(std::size_t line) { return "line " + std::to_string(line); }
std::string byteAt(std::size_t offset) { return "byte " + std::to_string(offset); }

std::string quoted(std::string_view text)
{
    // Long garbage (a binary file read as text) would swamp the message.
    constexpr std::size_t maxChars = 40;
    std::string s(text.substr(0, maxChars));
    for (char& c : s)
        if (!std::isprint(static_cast<unsigned char>(c)))
            c = '?';
    return "'" + s + (text.size() > maxChars ? "...'" : "'");
}

std::string supportedList()
{
    std::string s;
    for (const std::string& e : supportedMeshExtensions())
        s += (s.empty() ? "." : ", .") + e;
    return "supported mesh formats are " + s;
}

std::string lowerExtension(const std::string& path)
{
    std::string ext = std::filesystem::path(path).extension().string();
    if (!ext.empty() && ext.front() == '.')
        ext.erase(0, 1);
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

std::string readWholeFile(const std::string& path)
{
    Result<std::string> file = readRegularFile(path, {kMaxMeshFileBytes, "mesh", false});
    if (!file)
        fail(file.error().location, file.error().message);
    return std::move(file).value();
}

// ---------------------------------------------------------------------------------------------
// Numbers in text formats. std::from_chars is locale-independent (a Qt app may switch
// LC_NUMERIC to one with a decimal comma) and reports exactly how much of the token it used.

// Parses the whole token; false if it is not a number. Overflow gives +-inf and underflow 0,
// so the caller sees the value the file meant and can refuse non-finite values with context.
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

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f'; }

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

// Walks a text file line by line, numbering lines from 1 and dropping a trailing '\r'.
class LineWalker {
public:
    explicit LineWalker(std::string_view text) : m_text(text) {}

    bool next(std::string_view& line)
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

    std::size_t lineNumber() const { return m_line; }  // of the line next() returned last
    std::size_t offset() const { return m_pos; }       // of the line next() returns next

private:
    std::string_view m_text;
    std::size_t m_pos = 0;
    std::size_t m_nextLine = 1;
    std::size_t m_line = 0;
};

// ---------------------------------------------------------------------------------------------
// Collects vertices and polygons from any of the readers and triangulates as fans.
class MeshBuilder {
public:
    TriangleMesh mesh;
    std::size_t skippedFaces = 0;  // faces that gave no triangle: fewer than 3 distinct corners

    // Corners must already be checked against the vertex count.
    void addPolygon(const std::uint32_t* corners, std::size_t count)
    {
        bool any = false;
        for (std::size_t i = 1; i + 1 < count; ++i)
            any |= addTriangle(corners[0], corners[i], corners[i + 1]);
        if (!any)
            ++skippedFaces;
    }

    // A triangle that repeats a vertex has no area and no normal: dropped. Strips use such
    // triangles on purpose to turn corners, so their caller does not count them as problems.
    bool addTriangle(std::uint32_t a, std::uint32_t b, std::uint32_t c)
    {
        if (a == b || b == c || a == c)
            return false;
        mesh.triangles.emplace_back(a, b, c);
        return true;
    }
};

std::string plural(std::size_t n, const char* one, const char* many)
{
    return std::to_string(n) + " " + (n == 1 ? one : many);
}

// =============================================================================================
// PLY

enum class PlyType : std::uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

std::optional<PlyType> plyTypeFromName(std::string_view name)
{
    if (name == "char" || name == "int8") return PlyType::Int8;
    if (name == "uchar" || name == "uint8") return PlyType::UInt8;
    if (name == "short" || name == "int16") return PlyType::Int16;
    if (name == "ushort" || name == "uint16") return PlyType::UInt16;
    if (name == "int" || name == "int32") return PlyType::Int32;
    if (name == "uint" || name == "uint32") return PlyType::UInt32;
    if (name == "float" || name == "float32") return PlyType::Float32;
    if (name == "double" || name == "float64") return PlyType::Float64;
    return std::nullopt;
}

std::size_t plyTypeSize(PlyType type)
{
    switch (type) {
    case PlyType::Int8:
    case PlyType::UInt8: return 1;
    case PlyType::Int16:
    case PlyType::UInt16: return 2;
    case PlyType::Int32:
    case PlyType::UInt32:
    case PlyType::Float32: return 4;
    case PlyType::Float64: return 8;
    }
    return 1;
}

bool plyTypeIsInteger(PlyType type) { return type != PlyType::Float32 && type != PlyType::Float64; }

struct PlyProperty {
    std::string name;
    PlyType type = PlyType::Float32;  // of the value, or of each list entry
    bool isList = false;
    PlyType countType = PlyType::UInt8;
};

enum class PlyRole { Vertex, Face, Strips, Other };

struct PlyElement {
    std::string name;
    std::uint64_t count = 0;
    std::size_t headerLine = 0;
    std::vector<PlyProperty> properties;
    PlyRole role = PlyRole::Other;
    std::array<int, 3> xyz{-1, -1, -1};  // property indices of x, y, z (vertex)
    int cornerList = -1;                 // property index of the vertex index list (face, strips)
};

enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct PlyHeader {
    PlyFormat format = PlyFormat::Ascii;
    std::vector<PlyElement> elements;
    std::size_t dataOffset = 0;  // first byte after the end_header line
    std::size_t dataLine = 0;    // number of the first line after end_header
};

PlyHeader parsePlyHeader(std::string_view bytes)
{
    PlyHeader header;
    LineWalker lines(bytes);
    std::string_view line;
    std::vector<std::string_view> tokens;

    if (!lines.next(line) || line != "ply")
        fail(lineAt(1), "not a PLY file: it does not start with the line 'ply'");

    bool haveFormat = false;
    bool ended = false;
    while (lines.next(line)) {
        const std::string where = lineAt(lines.lineNumber());
        splitTokens(line, tokens);
        if (tokens.empty() || tokens[0] == "comment" || tokens[0] == "obj_info")
            continue;
        if (tokens[0] == "end_header") {
            ended = true;
            break;
        }
        if (tokens[0] == "format") {
            if (tokens.size() < 2)
                fail(where, "the 'format' line names no format");
            if (tokens[1] == "ascii")
                header.format = PlyFormat::Ascii;
            else if (tokens[1] == "binary_little_endian")
                header.format = PlyFormat::BinaryLittleEndian;
            else if (tokens[1] == "binary_big_endian")
                header.format = PlyFormat::BinaryBigEndian;
            else
                fail(where, "unknown PLY format " + quoted(tokens[1]) + " (expected ascii, binary_little_endian or binary_big_endian)");
            haveFormat = true;
        } else if (tokens[0] == "element") {
            std::int64_t count = 0;
            if (tokens.size() != 3 || !parseInteger(tokens[2], count) || count < 0)
                fail(where, "expected 'element <name> <count>'");
            PlyElement element;
            element.name = std::string(tokens[1]);
            element.count = static_cast<std::uint64_t>(count);
            element.headerLine = lines.lineNumber();
            header.elements.push_back(std::move(element));
        } else if (tokens[0] == "property") {
            if (header.elements.empty())
                fail(where, "a 'property' line comes before any 'element' line");
            PlyProperty property;
            if (tokens.size() == 5 && tokens[1] == "list") {
                const auto countType = plyTypeFromName(tokens[2]);
                const auto itemType = plyTypeFromName(tokens[3]);
                if (!countType || !itemType)
                    fail(where, "unknown property type in " + quoted(line));
                if (!plyTypeIsInteger(*countType))
                    fail(where, "a list length must have an integer type, not " + quoted(tokens[2]));
                property.isList = true;
                property.countType = *countType;
                property.type = *itemType;
                property.name = std::string(tokens[4]);
            } else if (tokens.size() == 3) {
                const auto type = plyTypeFromName(tokens[1]);
                if (!type)
                    fail(where, "unknown property type " + quoted(tokens[1]));
                property.type = *type;
                property.name = std::string(tokens[2]);
            } else {
                fail(where, "expected 'property <type> <name>' or 'property list <type> <type> <name>'");
            }
            header.elements.back().properties.push_back(std::move(property));
        } else {
            fail(where, "unexpected header line " + quoted(line));
        }
    }
    if (!ended)
        fail({}, "the PLY header has no 'end_header' line: the file is cut short or is not a PLY file");
    if (!haveFormat)
        fail({}, "the PLY header has no 'format' line");
    header.dataOffset = lines.offset();
    header.dataLine = lines.lineNumber() + 1;

    // Decide what each element is for, and refuse what we cannot use.
    bool haveVertex = false;
    for (PlyElement& element : header.elements) {
        const std::string where = lineAt(element.headerLine);
        if (element.name == "vertex") {
            if (haveVertex)
                fail(where, "the file has two 'vertex' elements");
            haveVertex = true;
            element.role = PlyRole::Vertex;
            for (std::size_t i = 0; i < element.properties.size(); ++i) {
                const PlyProperty& p = element.properties[i];
                const int axis = p.name == "x" ? 0 : p.name == "y" ? 1 : p.name == "z" ? 2 : -1;
                if (axis >= 0 && !p.isList && element.xyz[axis] < 0)
                    element.xyz[axis] = static_cast<int>(i);
            }
            if (element.xyz[0] < 0 || element.xyz[1] < 0 || element.xyz[2] < 0)
                fail(where, "the 'vertex' element lacks an x, y or z property");
            // Triangles hold 32-bit indices.
            if (element.count > std::numeric_limits<std::uint32_t>::max())
                fail(where, "the file declares " + std::to_string(element.count) + " vertices, more than Wisp can index");
        } else if (element.name == "face" || element.name == "tristrips") {
            element.role = element.name == "face" ? PlyRole::Face : PlyRole::Strips;
            int onlyList = -1;
            int lists = 0;
            for (std::size_t i = 0; i < element.properties.size(); ++i) {
                const PlyProperty& p = element.properties[i];
                if (!p.isList)
                    continue;
                ++lists;
                onlyList = static_cast<int>(i);
                if (element.cornerList < 0 && (p.name == "vertex_indices" || p.name == "vertex_index"))
                    element.cornerList = static_cast<int>(i);
            }
            if (element.cornerList < 0 && lists == 1)
                element.cornerList = onlyList;
            if (element.cornerList < 0)
                fail(where, "the '" + element.name + "' element has no 'vertex_indices' list");
            if (!plyTypeIsInteger(element.properties[static_cast<std::size_t>(element.cornerList)].type))
                fail(where, "the '" + element.name + "' element stores vertex indices as floating-point numbers");
        }
    }
    if (!haveVertex)
        fail({}, "the PLY file has no 'vertex' element");
    return header;
}

// Refuses a header that promises more items than the bytes after it could hold, before any
// memory is reserved for them: a corrupt count must not allocate gigabytes.
void checkPlyCountsAgainstSize(const PlyHeader& header, std::size_t fileSize)
{
    std::uint64_t remaining = fileSize - header.dataOffset;
    for (const PlyElement& element : header.elements) {
        // The least one item can take: binary, every scalar and every list length; ASCII, one
        // character and one separator per value (the file's last value may lack the separator).
        std::uint64_t minItemBytes = 0;
        for (const PlyProperty& p : element.properties) {
            if (header.format == PlyFormat::Ascii)
                minItemBytes += 2;
            else
                minItemBytes += plyTypeSize(p.isList ? p.countType : p.type);
        }
        if (minItemBytes == 0 || element.count == 0)
            continue;
        const std::uint64_t slack = header.format == PlyFormat::Ascii ? 1 : 0;
        if (element.count > (remaining + slack) / minItemBytes)
            fail(lineAt(element.headerLine),
                 "the header declares " + std::to_string(element.count) + " items of element '" + element.name +
                     "', but only " + std::to_string(fileSize - header.dataOffset) +
                     " bytes of data follow the header: the file is truncated or its header is wrong");
        remaining -= std::min(remaining, element.count * minItemBytes);
    }
}

// Where the reader is, for messages about the file ending early.
struct PlyProgress {
    const PlyElement* element = nullptr;
    std::uint64_t item = 0;

    std::string describe() const
    {
        if (!element)
            return {};
        return " in element '" + element->name + "', item " + std::to_string(item) + " of " +
               std::to_string(element->count) + " (numbered from 0)";
    }
};

template <typename T>
T loadScalar(const char* p, bool swapBytes)
{
    std::array<char, sizeof(T)> raw;
    std::memcpy(raw.data(), p, sizeof(T));
    if (swapBytes)
        std::reverse(raw.begin(), raw.end());
    T value;
    std::memcpy(&value, raw.data(), sizeof(T));
    return value;
}

class PlyBinaryCursor {
public:
    PlyBinaryCursor(std::string_view bytes, std::size_t offset, bool swapBytes, const PlyProgress& progress)
        : m_bytes(bytes), m_pos(offset), m_swap(swapBytes), m_progress(progress)
    {
    }

    double number(PlyType type)
    {
        const char* p = take(plyTypeSize(type));
        switch (type) {
        case PlyType::Int8: return loadScalar<std::int8_t>(p, m_swap);
        case PlyType::UInt8: return loadScalar<std::uint8_t>(p, m_swap);
        case PlyType::Int16: return loadScalar<std::int16_t>(p, m_swap);
        case PlyType::UInt16: return loadScalar<std::uint16_t>(p, m_swap);
        case PlyType::Int32: return loadScalar<std::int32_t>(p, m_swap);
        case PlyType::UInt32: return loadScalar<std::uint32_t>(p, m_swap);
        case PlyType::Float32: return loadScalar<float>(p, m_swap);
        case PlyType::Float64: return loadScalar<double>(p, m_swap);
        }
        return 0.0;
    }

    // Only called for integer types (the header check guarantees it); every PLY integer type fits a
    // double exactly, so one reader serves both.
    std::int64_t integer(PlyType type)
    {
        if (type == PlyType::Float32 || type == PlyType::Float64)
            fail(location(), "internal error: integer read from a floating-point property");
        return static_cast<std::int64_t>(number(type));
    }

    void skip(PlyType type) { take(plyTypeSize(type)); }
    void skipList(std::uint64_t count, PlyType type) { take(static_cast<std::size_t>(count) * plyTypeSize(type)); }

    bool canHoldList(std::uint64_t count, PlyType type) const
    {
        return count <= (m_bytes.size() - m_pos) / plyTypeSize(type);
    }

    std::size_t mark() const { return m_last; }
    std::string locationOf(std::size_t mark) const { return byteAt(mark); }
    std::string location() const { return byteAt(m_last); }

    std::string trailingWarning() const
    {
        if (m_pos >= m_bytes.size())
            return {};
        return plural(m_bytes.size() - m_pos, "byte", "bytes") + " after the last element were ignored";
    }

private:
    const char* take(std::size_t n)
    {
        if (m_bytes.size() - m_pos < n)
            fail(byteAt(m_pos), "the file ends early" + m_progress.describe() + ": it is truncated, or its header promises more than it holds");
        m_last = m_pos;
        const char* p = m_bytes.data() + m_pos;
        m_pos += n;
        return p;
    }

    std::string_view m_bytes;
    std::size_t m_pos = 0;
    std::size_t m_last = 0;
    bool m_swap = false;
    const PlyProgress& m_progress;
};

class PlyAsciiCursor {
public:
    PlyAsciiCursor(std::string_view bytes, std::size_t offset, std::size_t line, const PlyProgress& progress)
        : m_bytes(bytes), m_pos(offset), m_line(line), m_last(line), m_progress(progress)
    {
    }

    double number(PlyType)
    {
        const std::string_view t = token();
        double value = 0.0;
        if (!parseDouble(t, value))
            fail(location(), quoted(t) + " is not a number" + m_progress.describe());
        return value;
    }

    std::int64_t integer(PlyType)
    {
        const std::string_view t = token();
        std::int64_t value = 0;
        if (parseInteger(t, value))
            return value;
        // Some writers print integers as "3.0".
        double d = 0.0;
        if (parseDouble(t, d) && std::floor(d) == d && std::abs(d) < 9.0e15)
            return static_cast<std::int64_t>(d);
        fail(location(), quoted(t) + " is not a whole number" + m_progress.describe());
    }

    void skip(PlyType) { token(); }
    void skipList(std::uint64_t count, PlyType)
    {
        for (std::uint64_t i = 0; i < count; ++i)
            token();
    }

    // Each value needs at least a character and a separator.
    bool canHoldList(std::uint64_t count, PlyType) const { return count <= (m_bytes.size() - m_pos) / 2 + 1; }

    std::size_t mark() const { return m_last; }
    std::string locationOf(std::size_t mark) const { return lineAt(mark); }
    std::string location() const { return lineAt(m_last); }

    std::string trailingWarning()
    {
        skipSpace();
        if (m_pos >= m_bytes.size())
            return {};
        return "text after the last element (from line " + std::to_string(m_line) + ") was ignored";
    }

private:
    void skipSpace()
    {
        while (m_pos < m_bytes.size() && isSpace(m_bytes[m_pos])) {
            if (m_bytes[m_pos] == '\n')
                ++m_line;
            ++m_pos;
        }
    }

    std::string_view token()
    {
        skipSpace();
        if (m_pos >= m_bytes.size())
            fail(lineAt(m_line), "the file ends early" + m_progress.describe() + ": it is truncated, or its header promises more than it holds");
        const std::size_t start = m_pos;
        while (m_pos < m_bytes.size() && !isSpace(m_bytes[m_pos]))
            ++m_pos;
        m_last = m_line;
        return m_bytes.substr(start, m_pos - start);
    }

    std::string_view m_bytes;
    std::size_t m_pos = 0;
    std::size_t m_line = 1;
    std::size_t m_last = 1;
    const PlyProgress& m_progress;
};

template <typename Cursor>
void readPlyBody(const PlyHeader& header, Cursor& cursor, PlyProgress& progress, MeshBuilder& builder,
                 std::vector<std::string>& warnings)
{
    std::uint32_t vertexCount = 0;
    for (const PlyElement& element : header.elements) {
        if (element.role == PlyRole::Vertex)
            vertexCount = static_cast<std::uint32_t>(element.count);
    }

    std::vector<std::int64_t> list;
    std::vector<std::uint32_t> corners;

    // Checks one index and says which item of which element used it, so the artist can find it.
    const auto checkedIndex = [&](const PlyElement& element, std::uint64_t item, std::int64_t index, std::size_t mark) {
        if (index < 0 || index >= static_cast<std::int64_t>(vertexCount))
            fail(cursor.locationOf(mark), (element.role == PlyRole::Face ? "face " : "triangle strip list ") +
                                              std::to_string(item) + " refers to vertex " + std::to_string(index) +
                                              ", but the file has " + std::to_string(vertexCount) +
                                              " vertices (numbered from 0)");
        return static_cast<std::uint32_t>(index);
    };

    for (const PlyElement& element : header.elements) {
        progress.element = &element;
        if (element.role == PlyRole::Other && element.count > 0)
            warnings.push_back("ignored the PLY element '" + element.name + "' (" + std::to_string(element.count) + " items)");
        if (element.properties.empty())
            continue;  // nothing stored per item, so nothing to read however large the count
        if (element.role == PlyRole::Vertex)
            builder.mesh.positions.reserve(element.count);  // checked against the file size already
        if (element.role == PlyRole::Face)
            builder.mesh.triangles.reserve(builder.mesh.triangles.size() + element.count);

        const std::size_t propertyCount = element.properties.size();
        for (std::uint64_t item = 0; item < element.count; ++item) {
            progress.item = item;
            std::array<double, 3> xyz{0.0, 0.0, 0.0};
            for (std::size_t k = 0; k < propertyCount; ++k) {
                const PlyProperty& p = element.properties[k];
                if (!p.isList) {
                    if (element.role == PlyRole::Vertex) {
                        const int kk = static_cast<int>(k);
                        if (kk == element.xyz[0])
                            xyz[0] = cursor.number(p.type);
                        else if (kk == element.xyz[1])
                            xyz[1] = cursor.number(p.type);
                        else if (kk == element.xyz[2])
                            xyz[2] = cursor.number(p.type);
                        else
                            cursor.skip(p.type);
                    } else {
                        cursor.skip(p.type);
                    }
                    continue;
                }
                const std::int64_t length = cursor.integer(p.countType);
                const std::size_t mark = cursor.mark();
                if (length < 0)
                    fail(cursor.location(), "a list has a negative length" + progress.describe());
                if (!cursor.canHoldList(static_cast<std::uint64_t>(length), p.type))
                    fail(cursor.location(), "a list claims " + std::to_string(length) +
                                                " entries, more than the rest of the file holds" + progress.describe());
                if (static_cast<int>(k) != element.cornerList) {
                    cursor.skipList(static_cast<std::uint64_t>(length), p.type);
                    continue;
                }
                list.resize(static_cast<std::size_t>(length));
                for (std::int64_t& value : list)
                    value = cursor.integer(p.type);

                if (element.role == PlyRole::Face) {
                    corners.resize(list.size());
                    for (std::size_t i = 0; i < list.size(); ++i)
                        corners[i] = checkedIndex(element, item, list[i], mark);
                    builder.addPolygon(corners.data(), corners.size());
                    continue;
                }
                // Strips: -1 ends a strip; triangle k of a strip is (s[k], s[k+1], s[k+2]) with the
                // first two swapped on odd k, so every triangle keeps the first one's winding.
                std::size_t start = 0;
                for (std::size_t i = 0; i <= list.size(); ++i) {
                    if (i < list.size() && list[i] != -1) {
                        checkedIndex(element, item, list[i], mark);
                        continue;
                    }
                    for (std::size_t t = start; t + 2 < i; ++t) {
                        auto a = static_cast<std::uint32_t>(list[t]);
                        auto b = static_cast<std::uint32_t>(list[t + 1]);
                        const auto c = static_cast<std::uint32_t>(list[t + 2]);
                        if ((t - start) % 2 == 1)
                            std::swap(a, b);
                        builder.addTriangle(a, b, c);
                    }
                    start = i + 1;
                }
            }
            if (element.role == PlyRole::Vertex)
                builder.mesh.positions.emplace_back(static_cast<float>(xyz[0]), static_cast<float>(xyz[1]),
                                                    static_cast<float>(xyz[2]));
        }
    }
    progress.element = nullptr;
    const std::string trailing = cursor.trailingWarning();
    if (!trailing.empty())
        warnings.push_back(trailing);
}

void readPly(std::string_view bytes, MeshBuilder& builder, std::vector<std::string>& warnings)
{
    const PlyHeader header = parsePlyHeader(bytes);
    checkPlyCountsAgainstSize(header, bytes.size());
    PlyProgress progress;
    if (header.format == PlyFormat::Ascii) {
        PlyAsciiCursor cursor(bytes, header.dataOffset, header.dataLine, progress);
        readPlyBody(header, cursor, progress, builder, warnings);
    } else {
        const bool fileIsLittle = header.format == PlyFormat::BinaryLittleEndian;
        const bool swapBytes = fileIsLittle != (std::endian::native == std::endian::little);
        PlyBinaryCursor cursor(bytes, header.dataOffset, swapBytes, progress);
        readPlyBody(header, cursor, progress, builder, warnings);
    }
}

// =============================================================================================
// OFF (ASCII). One vertex per line (x y z, then optional normal, colour, texture coordinates,
// ignored) and one face per line (n i1 ... in, then an optional colour, ignored); '#' starts a
// comment. Written here rather than through OpenMesh because OpenMesh's OFF reader trusts every
// count it reads: a face claiming 4 billion corners makes it push 4 billion indices.

class OffLines {
public:
    explicit OffLines(std::string_view text) : m_walker(text) {}

    // The next line with something on it besides a comment.
    bool next(std::vector<std::string_view>& tokens)
    {
        std::string_view line;
        while (m_walker.next(line)) {
            const std::size_t hash = line.find('#');
            if (hash != std::string_view::npos)
                line = line.substr(0, hash);
            splitTokens(line, tokens);
            if (!tokens.empty())
                return true;
        }
        return false;
    }

    std::string location() const { return lineAt(m_walker.lineNumber()); }
    std::size_t remainingBytes(std::size_t total) const { return total - std::min(total, m_walker.offset()); }

private:
    LineWalker m_walker;
};

void readOff(std::string_view bytes, MeshBuilder& builder)
{
    OffLines lines(bytes);
    std::vector<std::string_view> tokens;
    if (!lines.next(tokens))
        fail({}, "the file holds only comments and blank lines");

    // Keyword: [ST][C][N][4][n]OFF, optionally followed by BINARY.
    std::string_view keyword = tokens[0];
    if (keyword.size() < 3 || keyword.substr(keyword.size() - 3) != "OFF" ||
        keyword.substr(0, keyword.size() - 3).find_first_not_of("STCN4n") != std::string_view::npos)
        fail(lines.location(), "not an OFF file: it should start with 'OFF', not " + quoted(keyword));
    const std::string_view prefix = keyword.substr(0, keyword.size() - 3);
    if (prefix.find('4') != std::string_view::npos || prefix.find('n') != std::string_view::npos)
        fail(lines.location(), "4-dimensional and n-dimensional OFF files are not supported");
    if (tokens.size() > 1 && tokens[1] == "BINARY")
        fail(lines.location(), "binary OFF is not supported; save the mesh as ASCII OFF, PLY or OBJ");

    // The counts may share the keyword's line.
    std::vector<std::string_view> counts(tokens.begin() + 1, tokens.end());
    if (counts.empty()) {
        if (!lines.next(tokens))
            fail(lines.location(), "the file ends before the vertex and face counts");
        counts = tokens;
    }
    std::int64_t vertexCount = 0;
    std::int64_t faceCount = 0;
    if (counts.size() < 2 || !parseInteger(counts[0], vertexCount) || !parseInteger(counts[1], faceCount) ||
        vertexCount < 0 || faceCount < 0)
        fail(lines.location(), "expected the counts '<vertices> <faces> <edges>'");
    // A vertex line takes at least 5 bytes ("0 0 0"), a face line at least 2 ("0\n").
    const std::size_t remaining = lines.remainingBytes(bytes.size());
    if (static_cast<std::uint64_t>(vertexCount) > remaining / 5 + 1 || static_cast<std::uint64_t>(faceCount) > remaining / 2 + 1)
        fail(lines.location(), "the header declares " + std::to_string(vertexCount) + " vertices and " +
                                   std::to_string(faceCount) + " faces, more than the " + std::to_string(remaining) +
                                   " bytes after it can hold: the file is truncated or the counts are wrong");
    if (vertexCount > static_cast<std::int64_t>(std::numeric_limits<std::uint32_t>::max()))
        fail(lines.location(), "too many vertices for Wisp to index");

    builder.mesh.positions.reserve(static_cast<std::size_t>(vertexCount));
    for (std::int64_t i = 0; i < vertexCount; ++i) {
        if (!lines.next(tokens))
            fail(lines.location(), "the file ends after " + std::to_string(i) + " of " + std::to_string(vertexCount) + " vertices");
        std::array<double, 3> xyz{};
        if (tokens.size() < 3)
            fail(lines.location(), "a vertex needs three coordinates");
        for (int k = 0; k < 3; ++k)
            if (!parseDouble(tokens[static_cast<std::size_t>(k)], xyz[static_cast<std::size_t>(k)]))
                fail(lines.location(), "vertex coordinate " + quoted(tokens[static_cast<std::size_t>(k)]) + " is not a number");
        builder.mesh.positions.emplace_back(static_cast<float>(xyz[0]), static_cast<float>(xyz[1]), static_cast<float>(xyz[2]));
    }

    std::vector<std::uint32_t> corners;
    builder.mesh.triangles.reserve(static_cast<std::size_t>(faceCount));
    for (std::int64_t f = 0; f < faceCount; ++f) {
        if (!lines.next(tokens))
            fail(lines.location(), "the file ends after " + std::to_string(f) + " of " + std::to_string(faceCount) + " faces");
        std::int64_t n = 0;
        if (!parseInteger(tokens[0], n) || n < 0)
            fail(lines.location(), "a face should start with its number of corners, not " + quoted(tokens[0]));
        if (static_cast<std::uint64_t>(n) > tokens.size() - 1)
            fail(lines.location(), "face " + std::to_string(f) + " lists " + std::to_string(n) + " corners but the line holds only " +
                                       std::to_string(tokens.size() - 1) + " numbers");
        corners.resize(static_cast<std::size_t>(n));
        for (std::size_t k = 0; k < corners.size(); ++k) {
            std::int64_t index = 0;
            if (!parseInteger(tokens[k + 1], index))
                fail(lines.location(), "face corner " + quoted(tokens[k + 1]) + " is not a vertex index");
            if (index < 0 || index >= vertexCount)
                fail(lines.location(), "face " + std::to_string(f) + " refers to vertex " + std::to_string(index) +
                                           ", but the file has " + std::to_string(vertexCount) + " vertices (numbered from 0)");
            corners[k] = static_cast<std::uint32_t>(index);
        }
        builder.addPolygon(corners.data(), corners.size());
    }
}

// =============================================================================================
// OpenMesh (OBJ, STL)

// OpenMesh's readers and its omerr()/omlog() streams are process-wide state.
std::mutex& openMeshMutex()
{
    static std::mutex mutex;
    return mutex;
}

// While alive, OpenMesh's error stream writes into a string instead of std::cerr and its log
// streams are silent; the returned error is ours, and OpenMesh's remarks become warnings.
// omerr() is a std::ostream, so its buffer is swapped: connecting a target to OpenMesh's
// multiplexer instead would leak, because its disconnect() never deletes the target.
class OpenMeshStreamCapture {
public:
    OpenMeshStreamCapture()
        : m_previous(::omerr().rdbuf(&m_text))
        , m_logWasEnabled(::omlog().is_enabled())
        , m_outWasEnabled(::omout().is_enabled())
    {
        ::omlog().disable();
        ::omout().disable();
    }

    ~OpenMeshStreamCapture()
    {
        ::omerr().flush();
        ::omerr().rdbuf(m_previous);  // also clears any error state a reader left on the stream
        if (m_logWasEnabled)
            ::omlog().enable();
        if (m_outWasEnabled)
            ::omout().enable();
    }

    OpenMeshStreamCapture(const OpenMeshStreamCapture&) = delete;
    OpenMeshStreamCapture& operator=(const OpenMeshStreamCapture&) = delete;

    // Distinct non-empty lines, at most `limit` of them, then a count of the rest.
    std::vector<std::string> lines(std::size_t limit = 8)
    {
        ::omerr().flush();
        std::vector<std::string> out;
        std::set<std::string> seen;
        std::size_t dropped = 0;
        std::istringstream in(m_text.str());
        std::string line;
        while (std::getline(in, line)) {
            const std::size_t b = line.find_first_not_of(" \t\r");
            if (b == std::string::npos)
                continue;
            line = line.substr(b, line.find_last_not_of(" \t\r") - b + 1);
            if (!seen.insert(line).second)
                continue;
            if (out.size() < limit)
                out.push_back(line);
            else
                ++dropped;
        }
        if (dropped > 0)
            out.push_back(plural(dropped, "more message", "more messages"));
        return out;
    }

private:
    std::stringbuf m_text;  // declared first: the constructor hands it to omerr()
    std::streambuf* m_previous;
    bool m_logWasEnabled;
    bool m_outWasEnabled;
};

// Receives what OpenMesh's readers parse. Keeps vertex numbering and every face as the file
// has them; an OpenMesh mesh would refuse or split non-manifold faces.
class CollectingImporter final : public OpenMesh::IO::BaseImporter {
public:
    CollectingImporter(MeshBuilder& builder, std::size_t fileSize) : m_builder(builder), m_limit(fileSize) {}

    OpenMesh::VertexHandle add_vertex(const OpenMesh::Vec3f& p) override
    {
        guardGrowth();
        m_builder.mesh.positions.emplace_back(p[0], p[1], p[2]);
        return OpenMesh::VertexHandle(static_cast<int>(m_builder.mesh.positions.size() - 1));
    }
    OpenMesh::VertexHandle add_vertex(const OpenMesh::Vec3d& p) override
    {
        return add_vertex(OpenMesh::Vec3f(static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])));
    }
    OpenMesh::VertexHandle add_vertex() override { return add_vertex(OpenMesh::Vec3f(0.0f, 0.0f, 0.0f)); }

    OpenMesh::FaceHandle add_face(const VHandles& handles) override
    {
        guardGrowth();
        const std::size_t n = m_builder.mesh.positions.size();
        m_corners.clear();
        for (const OpenMesh::VertexHandle& h : handles) {
            if (h.idx() < 0 || static_cast<std::size_t>(h.idx()) >= n)
                fail({}, "face " + std::to_string(m_faces + 1) + " refers to vertex " + std::to_string(h.idx() + 1) +
                             ", but the file has " + std::to_string(n) + " vertices");
            m_corners.push_back(static_cast<std::uint32_t>(h.idx()));
        }
        m_builder.addPolygon(m_corners.data(), m_corners.size());
        return OpenMesh::FaceHandle(static_cast<int>(m_faces++));
    }

    // Connectivity, attributes and textures: we ask for none, and keep none that arrive.
    OpenMesh::HalfedgeHandle add_edge(OpenMesh::VertexHandle, OpenMesh::VertexHandle) override { return OpenMesh::HalfedgeHandle(); }
    OpenMesh::FaceHandle add_face(OpenMesh::HalfedgeHandle) override { return OpenMesh::FaceHandle(); }
    void add_face_texcoords(OpenMesh::FaceHandle, OpenMesh::VertexHandle, const std::vector<OpenMesh::Vec2f>&) override {}
    void add_face_texcoords(OpenMesh::FaceHandle, OpenMesh::VertexHandle, const std::vector<OpenMesh::Vec3f>&) override {}
    void set_face_texindex(OpenMesh::FaceHandle, int) override {}
    void set_point(OpenMesh::VertexHandle, const OpenMesh::Vec3f&) override {}
    void set_halfedge(OpenMesh::VertexHandle, OpenMesh::HalfedgeHandle) override {}
    void set_normal(OpenMesh::VertexHandle, const OpenMesh::Vec3f&) override {}
    void set_normal(OpenMesh::VertexHandle, const OpenMesh::Vec3d&) override {}
    void set_color(OpenMesh::VertexHandle, const OpenMesh::Vec3uc&) override {}
    void set_color(OpenMesh::VertexHandle, const OpenMesh::Vec4uc&) override {}
    void set_color(OpenMesh::VertexHandle, const OpenMesh::Vec3f&) override {}
    void set_color(OpenMesh::VertexHandle, const OpenMesh::Vec4f&) override {}
    void set_texcoord(OpenMesh::VertexHandle, const OpenMesh::Vec2f&) override {}
    void set_status(OpenMesh::VertexHandle, const OpenMesh::Attributes::StatusInfo&) override {}
    void set_next(OpenMesh::HalfedgeHandle, OpenMesh::HalfedgeHandle) override {}
    void set_face(OpenMesh::HalfedgeHandle, OpenMesh::FaceHandle) override {}
    void request_face_texcoords2D() override {}
    void set_texcoord(OpenMesh::HalfedgeHandle, const OpenMesh::Vec2f&) override {}
    void set_texcoord(OpenMesh::VertexHandle, const OpenMesh::Vec3f&) override {}
    void set_texcoord(OpenMesh::HalfedgeHandle, const OpenMesh::Vec3f&) override {}
    void set_status(OpenMesh::HalfedgeHandle, const OpenMesh::Attributes::StatusInfo&) override {}
    void set_color(OpenMesh::EdgeHandle, const OpenMesh::Vec3uc&) override {}
    void set_color(OpenMesh::EdgeHandle, const OpenMesh::Vec4uc&) override {}
    void set_color(OpenMesh::EdgeHandle, const OpenMesh::Vec3f&) override {}
    void set_color(OpenMesh::EdgeHandle, const OpenMesh::Vec4f&) override {}
    void set_status(OpenMesh::EdgeHandle, const OpenMesh::Attributes::StatusInfo&) override {}
    void set_normal(OpenMesh::FaceHandle, const OpenMesh::Vec3f&) override {}
    void set_normal(OpenMesh::FaceHandle, const OpenMesh::Vec3d&) override {}
    void set_color(OpenMesh::FaceHandle, const OpenMesh::Vec3uc&) override {}
    void set_color(OpenMesh::FaceHandle, const OpenMesh::Vec4uc&) override {}
    void set_color(OpenMesh::FaceHandle, const OpenMesh::Vec3f&) override {}
    void set_color(OpenMesh::FaceHandle, const OpenMesh::Vec4f&) override {}
    void set_status(OpenMesh::FaceHandle, const OpenMesh::Attributes::StatusInfo&) override {}
    void add_texture_information(int, std::string) override {}
    // reserve() is left as the base's no-op on purpose: the counts come from the file.

    std::size_t n_vertices() const override { return m_builder.mesh.positions.size(); }
    std::size_t n_faces() const override { return m_faces; }
    std::size_t n_edges() const override { return 0; }

private:
    // Every vertex and face costs the file at least a byte; more means a reader is looping on
    // garbage, which must end in an error rather than exhaust memory.
    void guardGrowth()
    {
        if (m_builder.mesh.positions.size() + m_faces > m_limit ||
            m_builder.mesh.positions.size() >= static_cast<std::size_t>(std::numeric_limits<int>::max()))
            fail({}, "OpenMesh produced more vertices and faces than the file can hold; the file is corrupt");
    }

    MeshBuilder& m_builder;
    std::size_t m_limit;
    std::size_t m_faces = 0;
    std::vector<std::uint32_t> m_corners;
};

// What the scan of an OBJ file found; OpenMesh builds the mesh afterwards.
struct ObjScan {
    std::size_t vertexLines = 0;
    std::size_t faceLines = 0;
    std::size_t facesTooFewCorners = 0;  // OpenMesh skips them without telling the importer
    std::size_t lineElements = 0;
    std::size_t pointElements = 0;
};

// A coordinate OpenMesh's OBJ and STL readers can take: they read floats through a stream,
// which fails on nan, inf and anything beyond the float range, and then silently drop the
// vertex (OBJ) or keep a stale or zero value (STL).
bool parseFloatCoordinate(std::string_view token, std::string& problem)
{
    double value = 0.0;
    if (!parseDouble(token, value)) {
        problem = "vertex coordinate " + quoted(token) + " is not a number";
        return false;
    }
    if (!std::isfinite(value) || !std::isfinite(static_cast<float>(value))) {
        problem = "vertex coordinate " + quoted(token) + " is not a finite number";
        return false;
    }
    return true;
}

// OpenMesh's OBJ reader trims " \t\r\n", then skips a line that is empty, starts with '#' or
// starts with other whitespace ('\v', '\f'). Mirrored, so that both count the same lines.
bool objLineTokens(std::string_view line, std::vector<std::string_view>& tokens)
{
    const std::size_t first = line.find_first_not_of(" \t\r\n");
    if (first == std::string_view::npos || line[first] == '#' || isSpace(line[first]))
        return false;
    splitTokens(line.substr(first), tokens);
    return !tokens.empty();
}

// Finds what OpenMesh's OBJ reader would get wrong silently: a vertex line it cannot read
// (every later index then points at the wrong vertex) and face indices out of range (skipped
// with a line on std::cerr). Mirrors its rules: negative indices count back from the vertices
// seen so far; positive ones may refer to any vertex in the file.
ObjScan scanObj(std::string_view text)
{
    ObjScan scan;
    LineWalker lines(text);
    std::string_view line;
    std::vector<std::string_view> tokens;
    std::string problem;

    // Pass 1: count the vertex lines and check their numbers.
    while (lines.next(line)) {
        if (!objLineTokens(line, tokens) || tokens[0] != "v")
            continue;
        ++scan.vertexLines;
        if (tokens.size() < 4)
            fail(lineAt(lines.lineNumber()), "a vertex line needs three coordinates");
        for (std::size_t k = 1; k <= 3; ++k)
            if (!parseFloatCoordinate(tokens[k], problem))
                fail(lineAt(lines.lineNumber()), problem);
    }

    // Pass 2: faces.
    LineWalker faces(text);
    std::size_t verticesSoFar = 0;
    std::vector<std::int64_t> corners;
    while (faces.next(line)) {
        if (!objLineTokens(line, tokens))
            continue;
        const std::string_view keyword = tokens[0];
        if (keyword == "v") {
            ++verticesSoFar;
        } else if (keyword == "l") {
            ++scan.lineElements;
        } else if (keyword == "p") {
            ++scan.pointElements;
        } else if (keyword == "f") {
            ++scan.faceLines;
            corners.clear();
            for (std::size_t k = 1; k < tokens.size(); ++k) {
                const std::string_view corner = tokens[k].substr(0, tokens[k].find('/'));
                std::int64_t index = 0;
                if (!parseInteger(corner, index))
                    fail(lineAt(faces.lineNumber()), "face corner " + quoted(tokens[k]) + " does not start with a vertex index");
                if (index == 0)
                    fail(lineAt(faces.lineNumber()), "a face uses vertex index 0, but OBJ numbers vertices from 1");
                const std::int64_t resolved = index < 0 ? static_cast<std::int64_t>(verticesSoFar) + index + 1 : index;
                if (resolved < 1 || resolved > static_cast<std::int64_t>(scan.vertexLines))
                    fail(lineAt(faces.lineNumber()), "a face refers to vertex " + std::to_string(index) + ", but the file has " +
                                                         std::to_string(scan.vertexLines) + " vertices");
                corners.push_back(resolved);
            }
            std::sort(corners.begin(), corners.end());
            if (std::unique(corners.begin(), corners.end()) - corners.begin() < 3)
                ++scan.facesTooFewCorners;
        }
    }
    return scan;
}

// A binary STL is exactly 84 + 50 n bytes, n being the count at byte 80; this is also how
// OpenMesh decides between binary and ASCII.
bool isBinaryStl(std::string_view bytes, std::uint32_t& triangleCount)
{
    if (bytes.size() < 84)
        return false;
    triangleCount = loadScalar<std::uint32_t>(bytes.data() + 80, std::endian::native != std::endian::little);
    return bytes.size() == 84 + 50 * static_cast<std::uint64_t>(triangleCount);
}

// Checks what OpenMesh's STL reader would get wrong silently: a cut-short binary file (it would
// parse the bytes as ASCII and find nothing), non-finite coordinates (its vertex merging
// compares them with <, which NaN breaks), unreadable numbers in ASCII (it keeps zeros).
void scanStl(std::string_view bytes)
{
    std::uint32_t triangleCount = 0;
    if (isBinaryStl(bytes, triangleCount)) {
        const bool swapBytes = std::endian::native != std::endian::little;
        for (std::uint32_t t = 0; t < triangleCount; ++t) {
            const std::size_t record = 84 + 50 * static_cast<std::size_t>(t);
            for (int k = 0; k < 9; ++k) {  // three corners after the 12-byte facet normal
                const std::size_t at = record + 12 + 4 * static_cast<std::size_t>(k);
                if (!std::isfinite(loadScalar<float>(bytes.data() + at, swapBytes)))
                    fail(byteAt(at), "triangle " + std::to_string(t) + " has a non-finite coordinate");
            }
        }
        return;
    }

    // Not binary by size, so it must be ASCII, which starts with "solid" and holds no NUL bytes.
    // Anything else is a binary STL that is cut short or corrupt; OpenMesh would read its bytes
    // as text, find no facets and say nothing useful.
    const std::size_t firstChar = std::min(bytes.size(), bytes.find_first_not_of(" \t\r\n"));
    const bool looksAscii = bytes.substr(firstChar, 5) == "solid" && bytes.substr(0, 1024).find('\0') == std::string_view::npos;
    if (!looksAscii) {
        if (bytes.size() < 84)
            fail({}, "the file is too short for a binary STL (" + std::to_string(bytes.size()) +
                         " bytes; the header alone takes 84) and is not an ASCII STL (which starts with 'solid')");
        fail(byteAt(80), "binary STL header says " + std::to_string(triangleCount) + " triangles, which take " +
                             std::to_string(84 + 50 * static_cast<std::uint64_t>(triangleCount)) + " bytes, but the file has " +
                             std::to_string(bytes.size()) + ": it is truncated or corrupt");
    }

    // ASCII: after each line containing "outer" OpenMesh reads three lines as "vertex x y z".
    LineWalker lines(bytes);
    std::string_view line;
    std::vector<std::string_view> tokens;
    std::string problem;
    while (lines.next(line)) {
        if (line.find("outer") == std::string_view::npos && line.find("OUTER") == std::string_view::npos)
            continue;
        for (int k = 0; k < 3; ++k) {
            if (!lines.next(line))
                fail(lineAt(lines.lineNumber()), "the file ends inside a facet");
            splitTokens(line, tokens);
            if (tokens.size() < 4)
                fail(lineAt(lines.lineNumber()), "expected 'vertex x y z'");
            for (std::size_t c = 1; c <= 3; ++c)
                if (!parseFloatCoordinate(tokens[c], problem))
                    fail(lineAt(lines.lineNumber()), problem);
        }
    }
}

// The OBJ text with every `mtllib` statement turned into a comment. OpenMesh opens material
// libraries by the name the file gives (`mtllib /dev/zero`, a FIFO beside the file: it read or
// blocked forever); Wisp reads no materials, so none is opened. `ignored` gets their names.
std::string withoutMaterialLibraries(std::string_view bytes, std::vector<std::string>& ignored)
{
    std::string text(bytes);
    std::size_t lineStart = 0;
    while (lineStart < text.size()) {
        std::size_t lineEnd = text.find('\n', lineStart);
        if (lineEnd == std::string::npos)
            lineEnd = text.size();
        const std::size_t first = text.find_first_not_of(" \t", lineStart);
        if (first < lineEnd && text.compare(first, 6, "mtllib") == 0 &&
            (first + 6 == lineEnd || text[first + 6] == ' ' || text[first + 6] == '\t' || text[first + 6] == '\r')) {
            std::string name = text.substr(first + 6, lineEnd - first - 6);
            name.erase(0, std::min(name.find_first_not_of(" \t"), name.size()));
            while (!name.empty() && (name.back() == '\r' || name.back() == ' '))
                name.pop_back();
            ignored.push_back(name);
            text[first] = '#';
        }
        lineStart = lineEnd + 1;
    }
    return text;
}

std::vector<std::string> readWithOpenMesh(const std::string& path, const std::string& ext, std::string_view bytes,
                                          MeshBuilder& builder)
{
    const std::lock_guard<std::mutex> lock(openMeshMutex());
    OpenMeshStreamCapture capture;
    CollectingImporter importer(builder, bytes.size());
    OpenMesh::IO::Options options;  // no normals, colours or texture coordinates
    std::vector<std::string> materialLibraries;
    bool ok = false;
    if (ext == "obj") {
        // From memory: the file is read once, by io/RegularFile, and OpenMesh never opens a path.
        std::istringstream in(withoutMaterialLibraries(bytes, materialLibraries));
        ok = OpenMesh::IO::OBJReader().read(in, importer, options);
    } else {
        ok = OpenMesh::IO::STLReader().read(path, importer, options);
    }
    std::vector<std::string> remarks = capture.lines();
    if (!ok)
        fail({}, "OpenMesh could not read the file: " + (remarks.empty() ? std::string("it gave no reason") : remarks.front()));
    for (std::string& remark : remarks)
        remark.insert(0, "OpenMesh: ");
    for (const std::string& library : materialLibraries)
        remarks.push_back("ignored the material library '" + library + "': Wisp reads no materials");
    return remarks;
}

void readObj(const std::string& path, std::string_view bytes, MeshBuilder& builder, std::vector<std::string>& warnings)
{
    const ObjScan scan = scanObj(bytes);
    const std::vector<std::string> remarks = readWithOpenMesh(path, "obj", bytes, builder);
    // The scan accepted every vertex line, so OpenMesh must have read every one; if not, the
    // indices would be shifted and the mesh silently wrong.
    if (builder.mesh.positions.size() != scan.vertexLines)
        fail({}, "OpenMesh read " + std::to_string(builder.mesh.positions.size()) + " vertices, but the file has " +
                     std::to_string(scan.vertexLines) + " vertex lines");
    if (scan.facesTooFewCorners > 0)
        warnings.push_back("skipped " + plural(scan.facesTooFewCorners, "face", "faces") + " with fewer than 3 distinct corners");
    if (scan.lineElements > 0 || scan.pointElements > 0)
        warnings.push_back("ignored " + plural(scan.lineElements, "line element ('l')", "line elements ('l')") + " and " +
                           plural(scan.pointElements, "point element ('p')", "point elements ('p')"));
    warnings.insert(warnings.end(), remarks.begin(), remarks.end());

    if (builder.mesh.triangles.empty()) {
        std::string why = "the file has " + plural(scan.vertexLines, "vertex", "vertices") + " but no faces";
        if (scan.lineElements > 0 || scan.pointElements > 0)
            why += " (only " + plural(scan.lineElements, "line", "lines") + " and " + plural(scan.pointElements, "point", "points") +
                   ", which are not a surface)";
        else if (scan.faceLines > 0)
            why += " with 3 distinct corners";
        fail({}, why + "; a head mesh needs triangles or polygons");
    }
}

void readStl(const std::string& path, std::string_view bytes, MeshBuilder& builder, std::vector<std::string>& warnings)
{
    scanStl(bytes);
    const std::vector<std::string> remarks = readWithOpenMesh(path, "stl", bytes, builder);
    warnings.insert(warnings.end(), remarks.begin(), remarks.end());
    if (builder.mesh.triangles.empty())
        fail({}, "no triangles found: the file is not an STL ('solid ... facet ... outer loop ... vertex') or holds only degenerate facets");
}

}  // namespace

const std::vector<std::string>& supportedMeshExtensions()
{
    // Function-local so that other files' static initialisers may call this safely.
    static const std::vector<std::string> extensions = {"obj", "ply", "off", "stl", "gltf", "glb"};
    return extensions;
}

Result<MeshReadResult> readMesh(const std::string& path)
{
    try {
        const std::string ext = lowerExtension(path);
        if (ext.empty())
            fail({}, "the file name has no extension, so its format is unknown; " + supportedList());
        const std::vector<std::string>& known = supportedMeshExtensions();
        if (std::find(known.begin(), known.end(), ext) == known.end())
            fail({}, "'." + ext + "' files cannot be read as meshes; " + supportedList());
        // glTF reads its own file and the buffers beside it (io/GltfReader.h).
        if (ext == "gltf" || ext == "glb")
            return readGltf(path);

        const std::string bytes = readWholeFile(path);
        MeshBuilder builder;
        MeshReadResult result;
        if (ext == "ply")
            readPly(bytes, builder, result.warnings);
        else if (ext == "off")
            readOff(bytes, builder);
        else if (ext == "obj")
            readObj(path, bytes, builder, result.warnings);
        else
            readStl(path, bytes, builder, result.warnings);

        if (builder.skippedFaces > 0)
            result.warnings.push_back("skipped " + plural(builder.skippedFaces, "face", "faces") +
                                      " with fewer than 3 distinct corners");
        if (builder.mesh.triangles.empty()) {
            if (builder.mesh.positions.empty())
                fail({}, "the file holds no vertices and no faces");
            fail({}, "the file has " + plural(builder.mesh.positions.size(), "vertex", "vertices") +
                         " but no triangles; a head mesh needs a surface");
        }
        if (const std::string problem = validateMesh(builder.mesh); !problem.empty())
            fail({}, problem);
        result.mesh = std::move(builder.mesh);
        return result;
    } catch (const ReadFailure& failure) {
        return IoError{path, failure.location, failure.message};
    } catch (const std::bad_alloc&) {
        return IoError{path, {}, "not enough memory to read this mesh"};
    } catch (const std::exception& e) {
        return IoError{path, {}, std::string("unexpected error while reading: ") + e.what()};
    }
}

}  // namespace wisp::io
