#include "io/UsdaWriter.h"

#include "io/AtomicFile.h"

#include <charconv>
#include <cmath>
#include <ostream>

namespace wisp::io {

namespace {

// The shortest decimal that reads back as the same float (std::to_chars' guarantee).
void appendNumber(std::string& out, float v)
{
    char text[32];
    const auto end = std::to_chars(text, text + sizeof text, v).ptr;
    out.append(text, end);
}

void appendNumber(std::string& out, double v)
{
    char text[40];
    const auto end = std::to_chars(text, text + sizeof text, v).ptr;
    out.append(text, end);
}

void appendPoint(std::string& out, const glm::vec3& p)
{
    out += '(';
    appendNumber(out, p.x);
    out += ", ";
    appendNumber(out, p.y);
    out += ", ";
    appendNumber(out, p.z);
    out += ')';
}

// `[item, item, ...]`: appendItem(i) writes item i of `count`. Every USD array here is one.
template <class AppendItem> void appendArray(std::string& out, std::size_t count, AppendItem appendItem)
{
    out += '[';
    for (std::size_t i = 0; i < count; ++i) {
        if (i)
            out += ", ";
        appendItem(i);
    }
    out += ']';
}

bool finite(const glm::vec3& p)
{
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

// USD matrices act on row vectors (translation in the last row): its rows are glm's columns.
void appendMatrix(std::string& out, const glm::mat4& m)
{
    out += '(';
    for (int c = 0; c < 4; ++c) {
        out += c ? ", (" : "(";
        for (int r = 0; r < 4; ++r) {
            if (r)
                out += ", ";
            appendNumber(out, static_cast<double>(m[c][r]));
        }
        out += ')';
    }
    out += ')';
}

// `<declaration> = value`, or `<declaration>.timeSamples = { time: value, ... }` for an animation:
// appendValue(frame) writes the value of one frame.
template <class AppendValue>
void appendSampled(
    std::string& out, const char* indent, const char* declaration, const UsdaScene& scene, AppendValue appendValue)
{
    out += indent;
    out += declaration;
    if (!scene.animated) {
        out += " = ";
        appendValue(scene.frames.front());
        out += '\n';
        return;
    }
    out += ".timeSamples = {\n";
    for (const UsdaFrame& frame : scene.frames) {
        out += indent;
        out += "    ";
        appendNumber(out, frame.timeCode);
        out += ": ";
        appendValue(frame);
        out += ",\n";
    }
    out += indent;
    out += "}\n";
}

} // namespace

std::vector<float> taperedWidths(
    std::span<const std::uint32_t> offsets, std::span<const float> rootWidthOfStrand, float tipRatio)
{
    std::vector<float> widths(offsets.empty() ? 0 : offsets.back());
    for (std::size_t s = 0; s + 1 < offsets.size(); ++s) {
        const std::uint32_t first = offsets[s], n = offsets[s + 1] - first;
        const float root = s < rootWidthOfStrand.size() ? rootWidthOfStrand[s] : 0.0f;
        for (std::uint32_t i = 0; i < n; ++i) {
            const float t = n > 1 ? static_cast<float>(i) / static_cast<float>(n - 1) : 0.0f;
            widths[first + i] = root * (1.0f + (tipRatio - 1.0f) * t);
        }
    }
    return widths;
}

std::string usdaText(const UsdaScene& scene, std::string* error)
{
    auto refuse = [&](std::string message) {
        if (error)
            *error = std::move(message);
        return std::string();
    };
    if (scene.offsets.empty() || scene.offsets.front() != 0)
        return refuse("the strand offsets do not start at 0");
    for (std::size_t s = 1; s < scene.offsets.size(); ++s)
        if (scene.offsets[s] < scene.offsets[s - 1])
            return refuse("the strand offsets decrease at strand " + std::to_string(s - 1));
    const std::size_t points = scene.offsets.back();
    if (scene.frames.empty())
        return refuse("there is no frame to write");
    if (!scene.animated && scene.frames.size() != 1)
        return refuse("a still holds one frame, not " + std::to_string(scene.frames.size()));
    if (scene.widthsMetres.size() != points)
        return refuse(std::to_string(scene.widthsMetres.size()) + " widths for " + std::to_string(points) + " points");
    for (float w : scene.widthsMetres)
        if (!std::isfinite(w) || w < 0.0f)
            return refuse("a strand width is not a finite, non-negative number");
    if (!(scene.framesPerSecond > 0.0) || !std::isfinite(scene.framesPerSecond))
        return refuse("frames per second must be positive");
    for (std::size_t f = 0; f < scene.frames.size(); ++f) {
        const UsdaFrame& frame = scene.frames[f];
        std::string timeCode;
        appendNumber(timeCode, frame.timeCode);
        const std::string which = "frame " + std::to_string(f) + " (time code " + timeCode + ")";
        if (frame.positions.size() != points)
            return refuse(which + ": " + std::to_string(frame.positions.size()) + " points for strands of "
                + std::to_string(points));
        if (!std::isfinite(frame.timeCode) || (f > 0 && !(frame.timeCode > scene.frames[f - 1].timeCode)))
            return refuse(which + ": time codes must be finite and increasing");
        for (std::size_t i = 0; i < points; ++i)
            if (!finite(frame.positions[i]))
                return refuse(which + ": point " + std::to_string(i) + " is not finite");
        for (int c = 0; c < 4; ++c)
            if (!finite(glm::vec3(frame.headToWorld[c])) || !std::isfinite(frame.headToWorld[c][3]))
                return refuse(which + ": the head transform is not finite");
    }
    if (scene.head) {
        if (const std::string problem = validateMesh(*scene.head); !problem.empty())
            return refuse("the head cannot be exported: " + problem);
    }

    // Curves of two points or more (a linear BasisCurves curve needs two), and their points.
    std::vector<std::uint32_t> kept, keptPointIndices;
    for (std::uint32_t s = 0; s + 1 < scene.offsets.size(); ++s)
        if (scene.offsets[s + 1] - scene.offsets[s] >= 2) {
            kept.push_back(s);
            for (std::uint32_t i = scene.offsets[s]; i < scene.offsets[s + 1]; ++i)
                keptPointIndices.push_back(i);
        }
    const std::size_t keptPoints = keptPointIndices.size();

    std::string out;
    out.reserve(64 + scene.frames.size() * keptPoints * 36);
    out += "#usda 1.0\n(\n    defaultPrim = \"Wisp\"\n    doc = \"Wisp hair: " + std::to_string(kept.size())
        + " strands, " + std::to_string(keptPoints) + " points"
        + (scene.animated ? ", " + std::to_string(scene.frames.size()) + " frames" : std::string())
        + "; metres, +Y up\"\n    metersPerUnit = 1\n    upAxis = \"Y\"\n";
    if (scene.animated) {
        out += "    startTimeCode = ";
        appendNumber(out, scene.frames.front().timeCode);
        out += "\n    endTimeCode = ";
        appendNumber(out, scene.frames.back().timeCode);
        out += "\n    timeCodesPerSecond = ";
        appendNumber(out, scene.framesPerSecond);
        out += "\n    framesPerSecond = ";
        appendNumber(out, scene.framesPerSecond);
        out += "\n";
    }
    out += ")\n\ndef Xform \"Wisp\" (\n    kind = \"component\"\n)\n{\n";

    // The hair.
    out += "    def BasisCurves \"hair\"\n    {\n        uniform token type = \"linear\"\n"
           "        uniform token wrap = \"nonperiodic\"\n        int[] curveVertexCounts = ";
    appendArray(out, kept.size(),
        [&](std::size_t k) { out += std::to_string(scene.offsets[kept[k] + 1] - scene.offsets[kept[k]]); });
    out += "\n";
    appendSampled(out, "        ", "point3f[] points", scene, [&](const UsdaFrame& frame) {
        appendArray(out, keptPoints, [&](std::size_t i) { appendPoint(out, frame.positions[keptPointIndices[i]]); });
    });
    out += "        float[] widths = ";
    appendArray(out, keptPoints, [&](std::size_t i) { appendNumber(out, scene.widthsMetres[keptPointIndices[i]]); });
    out += " (\n            interpolation = \"vertex\"\n        )\n    }\n";

    // The head: its mesh in head space under an Xform that moves it.
    if (scene.head) {
        const TriangleMesh& head = *scene.head;
        out += "\n    def Xform \"head\"\n    {\n";
        appendSampled(out, "        ", "matrix4d xformOp:transform", scene,
            [&](const UsdaFrame& frame) { appendMatrix(out, frame.headToWorld); });
        out += "        uniform token[] xformOpOrder = [\"xformOp:transform\"]\n\n"
               "        def Mesh \"mesh\"\n        {\n            uniform token subdivisionScheme = \"none\"\n"
               "            int[] faceVertexCounts = ";
        appendArray(out, head.triangles.size(), [&](std::size_t) { out += '3'; });
        out += "\n            int[] faceVertexIndices = ";
        appendArray(out, head.triangles.size(), [&](std::size_t t) {
            const glm::uvec3& tri = head.triangles[t];
            out += std::to_string(tri.x) + ", " + std::to_string(tri.y) + ", " + std::to_string(tri.z);
        });
        out += "\n            point3f[] points = ";
        appendArray(out, head.positions.size(), [&](std::size_t v) { appendPoint(out, head.positions[v]); });
        out += "\n        }\n    }\n";
    }
    out += "}\n";
    return out;
}

Result<void> writeUsda(const std::string& path, const UsdaScene& scene)
{
    std::string error;
    const std::string text = usdaText(scene, &error);
    if (!error.empty())
        return IoError{ path, "", error };
    return writeFileAtomically(
        path, [&](std::ostream& out) { out.write(text.data(), static_cast<std::streamsize>(text.size())); });
}

} // namespace wisp::io
