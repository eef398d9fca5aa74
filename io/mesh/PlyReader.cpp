// PLY, ASCII and binary (both endians): `vertex` with x, y, z of any numeric type and any extra
// properties in any order, `face` and `tristrips` (strips split at -1, alternating winding)
// lists. Every count in the header is checked against the bytes that follow it before anything is
// reserved, so a corrupt count cannot allocate gigabytes or loop for minutes.

#include "io/ReadFailure.h"
#include "io/mesh/ByteReader.h"
#include "io/mesh/FormatReaders.h"
#include "io/mesh/Tokenizer.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace wisp::io::mesh {

namespace {

enum class PlyType : std::uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

std::optional<PlyType> plyTypeFromName(std::string_view name)
{
    if (name == "char" || name == "int8")
        return PlyType::Int8;
    if (name == "uchar" || name == "uint8")
        return PlyType::UInt8;
    if (name == "short" || name == "int16")
        return PlyType::Int16;
    if (name == "ushort" || name == "uint16")
        return PlyType::UInt16;
    if (name == "int" || name == "int32")
        return PlyType::Int32;
    if (name == "uint" || name == "uint32")
        return PlyType::UInt32;
    if (name == "float" || name == "float32")
        return PlyType::Float32;
    if (name == "double" || name == "float64")
        return PlyType::Float64;
    return std::nullopt;
}

std::size_t plyTypeSize(PlyType type)
{
    switch (type) {
    case PlyType::Int8:
    case PlyType::UInt8:
        return 1;
    case PlyType::Int16:
    case PlyType::UInt16:
        return 2;
    case PlyType::Int32:
    case PlyType::UInt32:
    case PlyType::Float32:
        return 4;
    case PlyType::Float64:
        return 8;
    }
    return 1;
}

bool plyTypeIsInteger(PlyType type)
{
    return type != PlyType::Float32 && type != PlyType::Float64;
}

struct PlyProperty {
    std::string name;
    PlyType type = PlyType::Float32; // of the value, or of each list entry
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
    std::array<int, 3> xyz{ -1, -1, -1 }; // property indices of x, y, z (vertex)
    int cornerList = -1; // property index of the vertex index list (face, strips)
};

enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct PlyHeader {
    PlyFormat format = PlyFormat::Ascii;
    std::vector<PlyElement> elements;
    std::size_t dataOffset = 0; // first byte after the end_header line
    std::size_t dataLine = 0; // number of the first line after end_header
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
                fail(where,
                    "unknown PLY format " + quoted(tokens[1])
                        + " (expected ascii, binary_little_endian or binary_big_endian)");
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
                fail(where,
                    "the file declares " + std::to_string(element.count) + " vertices, more than Wisp can index");
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
                "the header declares " + std::to_string(element.count) + " items of element '" + element.name
                    + "', but only " + std::to_string(fileSize - header.dataOffset)
                    + " bytes of data follow the header: the file is truncated or its header is wrong");
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
        return " in element '" + element->name + "', item " + std::to_string(item) + " of "
            + std::to_string(element->count) + " (numbered from 0)";
    }
};

class PlyBinaryCursor {
public:
    PlyBinaryCursor(std::string_view bytes, std::size_t offset, std::endian order, const PlyProgress& progress)
        : m_bytes(bytes)
        , m_pos(offset)
        , m_order(order)
        , m_progress(progress)
    {
    }

    double number(PlyType type)
    {
        const char* p = take(plyTypeSize(type));
        switch (type) {
        case PlyType::Int8:
            return loadScalar<std::int8_t>(p, m_order);
        case PlyType::UInt8:
            return loadScalar<std::uint8_t>(p, m_order);
        case PlyType::Int16:
            return loadScalar<std::int16_t>(p, m_order);
        case PlyType::UInt16:
            return loadScalar<std::uint16_t>(p, m_order);
        case PlyType::Int32:
            return loadScalar<std::int32_t>(p, m_order);
        case PlyType::UInt32:
            return loadScalar<std::uint32_t>(p, m_order);
        case PlyType::Float32:
            return loadScalar<float>(p, m_order);
        case PlyType::Float64:
            return loadScalar<double>(p, m_order);
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
            fail(byteAt(m_pos),
                "the file ends early" + m_progress.describe()
                    + ": it is truncated, or its header promises more than it holds");
        m_last = m_pos;
        const char* p = m_bytes.data() + m_pos;
        m_pos += n;
        return p;
    }

    std::string_view m_bytes;
    std::size_t m_pos = 0;
    std::size_t m_last = 0;
    std::endian m_order = std::endian::little;
    const PlyProgress& m_progress;
};

class PlyAsciiCursor {
public:
    PlyAsciiCursor(std::string_view bytes, std::size_t offset, std::size_t line, const PlyProgress& progress)
        : m_bytes(bytes)
        , m_pos(offset)
        , m_line(line)
        , m_last(line)
        , m_progress(progress)
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
            fail(lineAt(m_line),
                "the file ends early" + m_progress.describe()
                    + ": it is truncated, or its header promises more than it holds");
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
            fail(cursor.locationOf(mark),
                (element.role == PlyRole::Face ? "face " : "triangle strip list ") + std::to_string(item)
                    + " refers to vertex " + std::to_string(index) + ", but the file has " + std::to_string(vertexCount)
                    + " vertices (numbered from 0)");
        return static_cast<std::uint32_t>(index);
    };

    for (const PlyElement& element : header.elements) {
        progress.element = &element;
        if (element.role == PlyRole::Other && element.count > 0)
            warnings.push_back(
                "ignored the PLY element '" + element.name + "' (" + std::to_string(element.count) + " items)");
        if (element.properties.empty())
            continue; // nothing stored per item, so nothing to read however large the count
        if (element.role == PlyRole::Vertex)
            builder.mesh.positions.reserve(element.count); // checked against the file size already
        if (element.role == PlyRole::Face)
            builder.mesh.triangles.reserve(builder.mesh.triangles.size() + element.count);

        const std::size_t propertyCount = element.properties.size();
        for (std::uint64_t item = 0; item < element.count; ++item) {
            progress.item = item;
            std::array<double, 3> xyz{ 0.0, 0.0, 0.0 };
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
                    fail(cursor.location(),
                        "a list claims " + std::to_string(length) + " entries, more than the rest of the file holds"
                            + progress.describe());
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
                builder.mesh.positions.emplace_back(
                    static_cast<float>(xyz[0]), static_cast<float>(xyz[1]), static_cast<float>(xyz[2]));
        }
    }
    progress.element = nullptr;
    const std::string trailing = cursor.trailingWarning();
    if (!trailing.empty())
        warnings.push_back(trailing);
}
} // namespace

void readPly(std::string_view bytes, MeshBuilder& builder, std::vector<std::string>& warnings)
{
    const PlyHeader header = parsePlyHeader(bytes);
    checkPlyCountsAgainstSize(header, bytes.size());
    PlyProgress progress;
    if (header.format == PlyFormat::Ascii) {
        PlyAsciiCursor cursor(bytes, header.dataOffset, header.dataLine, progress);
        readPlyBody(header, cursor, progress, builder, warnings);
    } else {
        const std::endian order
            = header.format == PlyFormat::BinaryLittleEndian ? std::endian::little : std::endian::big;
        PlyBinaryCursor cursor(bytes, header.dataOffset, order, progress);
        readPlyBody(header, cursor, progress, builder, warnings);
    }
}

} // namespace wisp::io::mesh
