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

    // Curves of two points or more (a linear BasisCurves curve needs two).
    std::vector<std::uint32_t> kept;
    for (std::size_t s = 0; s + 1 < scene.offsets.size(); ++s)
        if (scene.offsets[s + 1] - scene.offsets[s] >= 2)
            kept.push_back(static_cast<std::uint32_t>(s));
    std::size_t keptPoints = 0;
    for (std::uint32_t s : kept)
        keptPoints += scene.offsets[s + 1] - scene.offsets[s];

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
           "        uniform token wrap = \"nonperiodic\"\n        int[] curveVertexCounts = [";
    for (std::size_t k = 0; k < kept.size(); ++k) {
        if (k)
            out += ", ";
        out += std::to_string(scene.offsets[kept[k] + 1] - scene.offsets[kept[k]]);
    }
    out += "]\n";
    auto appendPoints = [&](std::span<const glm::vec3> positions) {
        out += '[';
        bool first = true;
        for (std::uint32_t s : kept)
            for (std::uint32_t i = scene.offsets[s]; i < scene.offsets[s + 1]; ++i) {
                if (!first)
                    out += ", ";
                first = false;
                appendPoint(out, positions[i]);
            }
        out += ']';
    };
    if (scene.animated) {
        out += "        point3f[] points.timeSamples = {\n";
        for (const UsdaFrame& frame : scene.frames) {
            out += "            ";
            appendNumber(out, frame.timeCode);
            out += ": ";
            appendPoints(frame.positions);
            out += ",\n";
        }
        out += "        }\n";
    } else {
        out += "        point3f[] points = ";
        appendPoints(scene.frames.front().positions);
        out += "\n";
    }
    out += "        float[] widths = [";
    {
        bool first = true;
        for (std::uint32_t s : kept)
            for (std::uint32_t i = scene.offsets[s]; i < scene.offsets[s + 1]; ++i) {
                if (!first)
                    out += ", ";
                first = false;
                appendNumber(out, scene.widthsMetres[i]);
            }
    }
    out += "] (\n            interpolation = \"vertex\"\n        )\n    }\n";

    // The head: its mesh in head space under an Xform that moves it.
    if (scene.head) {
        out += "\n    def Xform \"head\"\n    {\n";
        if (scene.animated) {
            out += "        matrix4d xformOp:transform.timeSamples = {\n";
            for (const UsdaFrame& frame : scene.frames) {
                out += "            ";
                appendNumber(out, frame.timeCode);
                out += ": ";
                appendMatrix(out, frame.headToWorld);
                out += ",\n";
            }
            out += "        }\n";
        } else {
            out += "        matrix4d xformOp:transform = ";
            appendMatrix(out, scene.frames.front().headToWorld);
            out += "\n";
        }
        out += "        uniform token[] xformOpOrder = [\"xformOp:transform\"]\n\n"
               "        def Mesh \"mesh\"\n        {\n            uniform token subdivisionScheme = \"none\"\n"
               "            int[] faceVertexCounts = [";
        for (std::size_t t = 0; t < scene.head->triangles.size(); ++t)
            out += t ? ", 3" : "3";
        out += "]\n            int[] faceVertexIndices = [";
        for (std::size_t t = 0; t < scene.head->triangles.size(); ++t) {
            const glm::uvec3& tri = scene.head->triangles[t];
            if (t)
                out += ", ";
            out += std::to_string(tri.x) + ", " + std::to_string(tri.y) + ", " + std::to_string(tri.z);
        }
        out += "]\n            point3f[] points = [";
        for (std::size_t v = 0; v < scene.head->positions.size(); ++v) {
            if (v)
                out += ", ";
            appendPoint(out, scene.head->positions[v]);
        }
        out += "]\n        }\n    }\n";
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
