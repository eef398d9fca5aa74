#include "widgets/HairRenderer.h"

#include "widgets/HairSampling.h"
#include "widgets/HairShading.h"
#include "widgets/HairShadowMap.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include <QOpenGLShaderProgram>

#include <algorithm>
#include <cmath>
#include <limits>

namespace wisp {
namespace {

bool finitePoint(const glm::vec3& p)
{
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

// Offsets anyone may have built: non-decreasing and inside the point array, or nothing is drawn.
bool offsetsUsable(const HairCurves& strands)
{
    if (strands.offsets.empty())
        return false;
    for (std::size_t i = 1; i < strands.offsets.size(); ++i)
        if (strands.offsets[i] < strands.offsets[i - 1])
            return false;
    return strands.offsets.back() <= strands.positions.size();
}

bool sameLooks(std::span<const StrandLook> a, std::span<const StrandLook> b)
{
    return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](const StrandLook& x, const StrandLook& y) {
        return x.rootColour == y.rootColour && x.tipColour == y.tipColour
            && x.rootThicknessMetres == y.rootThicknessMetres;
    });
}

// What a point's w tells the shader (see hair.vert): the strand is skipped, takes the style's
// colours, or takes look k (kFirstLookTag + k; floats hold these integers exactly).
constexpr float kSkipTag = 0.0f;
constexpr float kStyleTag = 1.0f;
constexpr float kFirstLookTag = 2.0f;
// Plus wetness (0..1) times this: a fraction below 0.5, so rounding still finds the tag.
constexpr float kWetTagScale = 0.45f;

} // namespace

HairRenderer::~HairRenderer() = default;

bool HairRenderer::initialize(GlFunctions* gl)
{
    m_gl = gl;
    m_program = loadShaderProgram(QStringLiteral("hair"), &m_error);
    if (!m_program)
        return false;
    // Optional: without them, ribbons take the one-pass path.
    QString twoPassError;
    m_sampleProgram = loadTransformFeedbackProgram(
        gl, QStringLiteral("hair_samples"), { "t_clip", "t_colour", "t_side" }, &twoPassError);
    m_ribbonProgram = loadShaderProgram(QStringLiteral("hair_ribbon"), QStringLiteral("hair"), &twoPassError);
    // Optional too: without it, the viewport keeps GL's lines on a software rasteriser.
    QString worldError;
    m_worldProgram = loadTransformFeedbackProgram(
        gl, QStringLiteral("hair_sample_world"), { "t_position", "t_derivative", "t_root", "t_tip" }, &worldError);
    if (!m_worldProgram)
        qWarning("HairRenderer: no software path: %s", qPrintable(worldError));
    // WISP_ONE_PASS_RIBBONS: the one-pass path, to compare with (ViewportTest.RibbonsInTwoPasses...).
    if (qEnvironmentVariableIsSet("WISP_ONE_PASS_RIBBONS")) {
        m_sampleProgram.reset();
        m_ribbonProgram.reset();
    } else if (!m_sampleProgram || !m_ribbonProgram) {
        qWarning("HairRenderer: ribbons in one pass: %s", qPrintable(twoPassError));
        m_sampleProgram.reset();
        m_ribbonProgram.reset();
    }
    gl->glGenVertexArrays(1, &m_vao);
    gl->glGenBuffers(1, &m_layoutBuffer);
    gl->glGenBuffers(1, &m_indexBuffer);
    gl->glGenBuffers(1, &m_decimatedIndexBuffer);
    m_decimatedToleranceMetres = -1.0f;
    if (qEnvironmentVariableIsSet("WISP_NO_LINE_DECIMATION"))
        m_lineDecimation = false;
    gl->glGenBuffers(1, &m_pointBuffer);
    gl->glGenTextures(1, &m_pointTexture);
    gl->glGenBuffers(1, &m_lookBuffer);
    gl->glGenTextures(1, &m_lookTexture);
    gl->glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &m_maxTexels);

    gl->glBindVertexArray(m_vao);
    gl->glBindBuffer(GL_ARRAY_BUFFER, m_layoutBuffer);
    gl->glEnableVertexAttribArray(0);
    gl->glVertexAttribIPointer(0, 2, GL_UNSIGNED_INT, sizeof(glm::uvec2), nullptr);
    gl->glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m_indexBuffer); // recorded in the VAO
    // Sample k of the first pass is layout vertex 2k (its left edge): a stride of two vertices.
    gl->glGenVertexArrays(1, &m_sampleVao);
    gl->glBindVertexArray(m_sampleVao);
    gl->glEnableVertexAttribArray(0);
    gl->glVertexAttribIPointer(0, 2, GL_UNSIGNED_INT, 2 * sizeof(glm::uvec2), nullptr);
    gl->glGenBuffers(1, &m_sampleBuffer);
    gl->glGenTextures(1, &m_sampleTexture);
    m_sampleCapacity = 0;
    gl->glGenBuffers(1, &m_captureBuffer);
    m_captureCapacity = 0;
    gl->glGenBuffers(1, &m_worldBuffer);
    m_worldCapacity = 0;
    m_worldKey.reset();
    m_softwareSamples = 0;
    gl->glBindVertexArray(0);
    gl->glBindBuffer(GL_ARRAY_BUFFER, 0);

    for (QOpenGLShaderProgram* program : { m_program.get(), m_sampleProgram.get(), m_worldProgram.get() }) {
        if (!program)
            continue;
        program->bind();
        program->setUniformValue("u_points", 0);
        program->setUniformValue("u_looks", 1);
        program->release();
    }
    if (m_ribbonProgram) {
        m_ribbonProgram->bind();
        m_ribbonProgram->setUniformValue("u_samples", 0);
        m_ribbonProgram->release();
    }
    // Everything that came before this context (a reparented widget gets a new one) is gone.
    m_looks.clear();
    uploadLooks(); // storage even without looks: the shader's sampler must refer to something
    m_layout = HairStripLayout{};
    m_vertexCount = 0;
    m_pointCapacity = 0;
    checkGlErrors(gl, "HairRenderer::initialize");
    return true;
}

void HairRenderer::release()
{
    if (!m_gl)
        return;
    m_gl->glDeleteTextures(1, &m_sampleTexture);
    m_gl->glDeleteBuffers(1, &m_sampleBuffer);
    m_gl->glDeleteVertexArrays(1, &m_sampleVao);
    m_sampleTexture = m_sampleBuffer = m_sampleVao = 0;
    m_sampleCapacity = 0;
    m_gl->glDeleteBuffers(1, &m_captureBuffer);
    m_captureBuffer = 0;
    m_captureCapacity = 0;
    m_gl->glDeleteBuffers(1, &m_worldBuffer);
    m_worldBuffer = 0;
    m_worldCapacity = 0;
    m_worldKey.reset();
    m_softwareSamples = 0;
    m_worldProgram.reset();
    m_sampleProgram.reset();
    m_ribbonProgram.reset();
    m_gl->glDeleteTextures(1, &m_lookTexture);
    m_gl->glDeleteBuffers(1, &m_lookBuffer);
    m_gl->glDeleteTextures(1, &m_pointTexture);
    m_gl->glDeleteBuffers(1, &m_pointBuffer);
    m_gl->glDeleteBuffers(1, &m_indexBuffer);
    m_gl->glDeleteBuffers(1, &m_decimatedIndexBuffer);
    m_decimatedIndexBuffer = 0;
    m_decimatedToleranceMetres = -1.0f;
    m_gl->glDeleteBuffers(1, &m_layoutBuffer);
    m_gl->glDeleteVertexArrays(1, &m_vao);
    m_lookTexture = m_lookBuffer = m_pointTexture = m_pointBuffer = m_indexBuffer = m_layoutBuffer = m_vao = 0;
    m_looks.clear();
    m_program.reset();
    m_gl = nullptr;
    m_vertexCount = 0;
    m_pointCapacity = 0;
    m_layout = HairStripLayout{};
}

void HairRenderer::clear()
{
    m_vertexCount = 0;
    m_skippedStrands = 0;
}

void HairRenderer::rebuildLayout(std::span<const std::uint32_t> offsets)
{
    m_layout = buildHairStripLayout(offsets);
    ++m_worldRevision;
    m_gl->glBindBuffer(GL_ARRAY_BUFFER, m_layoutBuffer);
    m_gl->glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(m_layout.vertices.size() * sizeof(glm::uvec2)),
        m_layout.vertices.data(), GL_STATIC_DRAW);
    m_gl->glBindBuffer(GL_ARRAY_BUFFER, 0);

    // All six index lists in one buffer, one upload.
    std::vector<std::uint32_t> indices;
    for (int primitive = 0; primitive < 2; ++primitive) {
        const auto& lists = primitive == 0 ? m_layout.lines : m_layout.ribbons;
        for (std::size_t step = 0; step < lists.size(); ++step) {
            m_indexOffsets[static_cast<std::size_t>(primitive)][step] = indices.size() * sizeof(std::uint32_t);
            indices.insert(indices.end(), lists[step].indices.begin(), lists[step].indices.end());
        }
    }
    // The element buffer binding is VAO state: bind the VAO to touch it.
    m_gl->glBindVertexArray(m_vao);
    m_gl->glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(indices.size() * sizeof(std::uint32_t)),
        indices.data(), GL_STATIC_DRAW);
    m_gl->glBindVertexArray(0);
    m_vertexCount = static_cast<GLsizei>(m_layout.vertices.size());
    checkGlErrors(m_gl, "HairRenderer::rebuildLayout");
}

void HairRenderer::setLooks(std::span<const StrandLook> looks)
{
    if (!m_program || sameLooks(looks, m_looks))
        return;
    // More than a uint16 index can name would never be read.
    const std::size_t count = std::min<std::size_t>(looks.size(), 65536);
    m_looks.assign(looks.begin(), looks.begin() + static_cast<std::ptrdiff_t>(count));
    uploadLooks();
}

void HairRenderer::uploadLooks()
{
    ++m_worldRevision;
    // At least one look's worth of texels, so the texture always has storage.
    // The root texel's alpha carries the look's hair thickness (0: the style's).
    std::vector<glm::vec4> texels(2 * std::max<std::size_t>(m_looks.size(), 1), glm::vec4(0.0f));
    m_thickestLookMetres = 0.0f;
    for (std::size_t k = 0; k < m_looks.size(); ++k) {
        const float thickness = std::isfinite(m_looks[k].rootThicknessMetres)
            ? std::clamp(m_looks[k].rootThicknessMetres, 0.0f, 0.01f)
            : 0.0f;
        m_thickestLookMetres = std::max(m_thickestLookMetres, thickness);
        texels[2 * k] = glm::vec4(linearFromSrgb(m_looks[k].rootColour), thickness);
        texels[2 * k + 1] = glm::vec4(linearFromSrgb(m_looks[k].tipColour), 1.0f);
    }
    m_gl->glBindBuffer(GL_TEXTURE_BUFFER, m_lookBuffer);
    m_gl->glBufferData(
        GL_TEXTURE_BUFFER, static_cast<GLsizeiptr>(texels.size() * sizeof(glm::vec4)), texels.data(), GL_STATIC_DRAW);
    m_gl->glBindTexture(GL_TEXTURE_BUFFER, m_lookTexture);
    m_gl->glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, m_lookBuffer);
    m_gl->glBindTexture(GL_TEXTURE_BUFFER, 0);
    m_gl->glBindBuffer(GL_TEXTURE_BUFFER, 0);
    checkGlErrors(m_gl, "HairRenderer::uploadLooks");
}

void HairRenderer::upload(
    const HairCurves& strands, std::span<const std::uint16_t> lookOfStrand, std::span<const float> wetness)
{
    ++m_worldRevision;
    if (!m_program)
        return;
    const std::size_t pointCount = strands.positions.size();
    if (!offsetsUsable(strands) || strands.strandCount() == 0 || pointCount == 0
        || pointCount > static_cast<std::size_t>(m_maxTexels)) {
        clear();
        return;
    }
    if (!m_layout.matches(strands.offsets))
        rebuildLayout(strands.offsets);
    m_vertexCount = static_cast<GLsizei>(m_layout.vertices.size());

    m_gl->glBindBuffer(GL_TEXTURE_BUFFER, m_pointBuffer);
    const auto bytes = static_cast<GLsizeiptr>(pointCount * sizeof(glm::vec4));
    if (pointCount > m_pointCapacity) {
        m_gl->glBufferData(GL_TEXTURE_BUFFER, bytes, nullptr, GL_STREAM_DRAW);
        m_pointCapacity = pointCount;
        // The texture refers to the buffer's storage, which glBufferData just replaced.
        m_gl->glBindTexture(GL_TEXTURE_BUFFER, m_pointTexture);
        m_gl->glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, m_pointBuffer);
        m_gl->glBindTexture(GL_TEXTURE_BUFFER, 0);
    }
    // Invalidating the buffer lets the driver hand out fresh memory instead of waiting for the
    // previous frame's draw to finish reading it (orphaning).
    auto* mapped = static_cast<glm::vec4*>(
        m_gl->glMapBufferRange(GL_TEXTURE_BUFFER, 0, bytes, GL_MAP_WRITE_BIT | GL_MAP_INVALIDATE_BUFFER_BIT));
    if (!mapped) {
        m_gl->glBindBuffer(GL_TEXTURE_BUFFER, 0);
        clear();
        checkGlErrors(m_gl, "HairRenderer::upload (map)");
        return;
    }
    // One pass per strand: first find out whether it is finite, then copy it with the verdict (and
    // its look) in w. Into a copy kept here (the shadow map's hair passes on a software GL read it:
    // HairShadowRaster), then into the mapped buffer (which may be write-combined: never read).
    m_points.resize(pointCount);
    glm::vec4* out = m_points.data();
    m_skippedStrands = 0;
    glm::vec3 low(std::numeric_limits<float>::max());
    glm::vec3 high(-std::numeric_limits<float>::max());
    float longestSquared = 0.0f;
    const glm::vec3* points = strands.positions.data();
    const bool withLooks = lookOfStrand.size() == strands.strandCount() && !m_looks.empty();
    for (std::size_t s = 0; s < strands.strandCount(); ++s) {
        const std::uint32_t begin = strands.offsets[s];
        const std::uint32_t end = strands.offsets[s + 1];
        bool finite = true;
        for (std::uint32_t i = begin; i < end; ++i)
            finite = finite && finitePoint(points[i]);
        if (!finite && end - begin >= 2 && end - begin - 1 <= HairStripLayout::kMaxSegments)
            ++m_skippedStrands;
        if (!finite) {
            std::fill(out + begin, out + end, glm::vec4(0.0f, 0.0f, 0.0f, kSkipTag));
            continue;
        }
        const bool hasLook = withLooks && lookOfStrand[s] < m_looks.size();
        // Wet hair (sim/style/HairDryer.h) is drawn darker: its wetness rides in the tag's fraction.
        const float wet = wetness.size() == strands.strandCount() ? std::clamp(wetness[s], 0.0f, 1.0f) : 0.0f;
        const float tag
            = (hasLook ? kFirstLookTag + static_cast<float>(lookOfStrand[s]) : kStyleTag) + kWetTagScale * wet;
        for (std::uint32_t i = begin; i < end; ++i) {
            out[i] = glm::vec4(points[i], tag);
            low = glm::min(low, points[i]);
            high = glm::max(high, points[i]);
            if (i > begin) {
                const glm::vec3 segment = points[i] - points[i - 1];
                longestSquared = std::max(longestSquared, glm::dot(segment, segment));
            }
        }
    }
    m_bounds = low.x <= high.x ? Aabb{ low, high } : Aabb{};
    m_longestSegmentMetres = std::sqrt(longestSquared);
    std::copy(m_points.begin(), m_points.end(), mapped);
    m_gl->glUnmapBuffer(GL_TEXTURE_BUFFER);
    // A typical segment length (from up to 256 strands' first segments) and turn at a joint, to pick
    // how finely the curves are sampled for the zoom.
    double length = 0.0;
    int counted = 0;
    const std::size_t stride = std::max<std::size_t>(1, strands.strandCount() / 256);
    for (std::size_t s = 0; s < strands.strandCount(); s += stride) {
        const std::uint32_t begin = strands.offsets[s];
        if (strands.offsets[s + 1] - begin < 2)
            continue;
        const float segment = glm::length(points[begin + 1] - points[begin]);
        if (std::isfinite(segment)) {
            length += segment;
            ++counted;
        }
    }
    m_segmentMetres = counted > 0 ? static_cast<float>(length / counted) : 0.0f;
    m_turnRadians = typicalTurnRadians(strands);
    m_chordDeviations = chordDeviations(strands);
    m_decimatedToleranceMetres = -1.0f;
    m_gl->glBindBuffer(GL_TEXTURE_BUFFER, 0);
    checkGlErrors(m_gl, "HairRenderer::upload");
}

HairRenderer::DrawPlan HairRenderer::planDraw(
    const RenderView& view, const HairStyle& style, float fraction, bool coarse)
{
    DrawPlan plan;
    const auto [drawn, widthScale] = drawnShare(fraction);
    plan.drawn = drawn;
    plan.widthScale = widthScale;

    // Lines while even the nearest hair is at most about a pixel wide (a line is one pixel wide;
    // half a pixel more is not worth twice the primitives). The nearest hair is at most a head's
    // radius and a half in front of the head's centre.
    const float nearestDepth = std::max(-view.headCentreView.z - 1.5f * view.headRadiusMetres, 1e-3f);
    const float pixelsPerMetre = view.projection[1][1] * 0.5f * view.viewportPixels.y / nearestDepth;
    // A line is one pixel wide whatever its width: a wider strand drawn as a line would lose the
    // coverage the widening above gave it, so previews take ribbons past a pixel too (the preview
    // keeps the look's coverage; DisplayDensityTest checks it).
    const float thickest = std::max(style.hairThicknessMetres, m_thickestLookMetres);
    const float rootPixels = thickest * style.lockWidthScale * widthScale * pixelsPerMetre;
    plan.lines = rootPixels <= style.minWidthPixels + 0.5f;
    // Samples per segment: the fewest that keep chords within maxDeviationPixels of the curve at the
    // head's depth, for the hair's typical turn (HairSampling.h).
    const float centreDepth = std::max(-view.headCentreView.z, 1e-3f);
    const float segmentPixels = m_segmentMetres * view.projection[1][1] * 0.5f * view.viewportPixels.y / centreDepth;
    plan.stepIndex = coarse ? 2 : sampleStepIndex(segmentPixels, m_turnRadians, style.maxDeviationPixels);
    const auto primitive = plan.lines ? HairStripLayout::Primitive::Lines : HairStripLayout::Primitive::Ribbons;
    plan.list = &m_layout.indices(primitive, plan.stepIndex);
    plan.centreLine = &m_layout.lines[plan.stepIndex];
    plan.byteOffset = m_indexOffsets[plan.lines ? 0 : 1][plan.stepIndex];
    plan.centreLineByteOffset = m_indexOffsets[0][plan.stepIndex];
    plan.elementBuffer = m_indexBuffer;
    plan.indexCount = static_cast<GLsizei>(plan.list->prefix[drawn]);
    // Lines at one sample a segment leave out the points of straight runs: no chord strays more than
    // maxDeviationPixels from the points at the nearest hair's depth (HairLineDecimation.h).
    if (plan.lines && plan.stepIndex == kOneSampleStep && m_lineDecimation && pixelsPerMetre > 0.0f) {
        const float tolerance = style.maxDeviationPixels / pixelsPerMetre;
        if (m_decimatedToleranceMetres < 0.0f || tolerance < m_decimatedToleranceMetres
            || tolerance > 1.5f * m_decimatedToleranceMetres)
            rebuildDecimatedLines(tolerance);
        if (m_decimatedToleranceMetres >= 0.0f) {
            plan.elementBuffer = m_decimatedIndexBuffer;
            plan.byteOffset = 0;
            plan.centreLineByteOffset = 0;
            plan.list = &m_decimatedLines;
            plan.centreLine = &m_decimatedLines;
            plan.indexCount = static_cast<GLsizei>(m_decimatedLines.prefix[drawn]);
        }
    }
    return plan;
}

void HairRenderer::draw(const RenderView& view, const HairStyle& style, float fraction, bool coarse)
{
    m_lastDrawnStrands = 0;
    if (!m_program || m_vertexCount == 0 || m_layout.drawnStrands == 0)
        return;
    const DrawPlan plan = planDraw(view, style, fraction, coarse);
    const std::size_t drawn = plan.drawn;
    const float widthScale = plan.widthScale;
    const bool lines = plan.lines;
    const std::size_t stepIndex = plan.stepIndex;

    GlFunctions* gl = m_gl;
    gl->glEnable(GL_DEPTH_TEST);
    gl->glDepthMask(m_depthWrites ? GL_TRUE : GL_FALSE);
    gl->glDisable(GL_CULL_FACE); // the ribbon's winding flips with the strand's screen direction
    // Thin strands carry their coverage in alpha, which blending turns into thickness (with MSAA,
    // in each sample a strand covers). Not alpha-to-coverage: it gives every fragment of a pixel
    // the same samples for the same alpha, so overlapping thin strands do not add up, and on Mesa's
    // llvmpipe strands under a quarter of a pixel vanish (locks of hair tips went missing once the
    // viewport's MSAA really was on).
    gl->glEnable(GL_BLEND);
    gl->glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);

    // The first step's ribbons (the strands' full detail) in two passes, each sample evaluated
    // once; coarser steps skip samples the first pass would evaluate anyway, and lines have one
    // vertex per sample already.
    const std::size_t byteOffset = plan.byteOffset;
    const GLsizei indexCount = plan.indexCount;
    const GLuint elementBuffer = plan.elementBuffer;
    m_lastDrawnLineSegments = lines ? static_cast<std::size_t>(indexCount) - 2 * drawn : 0;
    // Ribbon strips hold two indices per sample and a restart per strand, in vertex order.
    const std::size_t samples = (m_layout.ribbons[0].prefix[drawn] - drawn) / 2;
    bool drawnInTwoPasses = false;
    if (!lines && stepIndex == 0 && m_sampleProgram) {
        setStrandUniforms(*m_sampleProgram, view, style, widthScale, lines);
        drawnInTwoPasses = drawRibbonsFromSamples(samples, indexCount, byteOffset);
    }
    if (!drawnInTwoPasses) {
        QOpenGLShaderProgram& program = *m_program;
        setStrandUniforms(program, view, style, widthScale, lines);
        gl->glActiveTexture(GL_TEXTURE1);
        gl->glBindTexture(GL_TEXTURE_BUFFER, m_lookTexture);
        gl->glActiveTexture(GL_TEXTURE0);
        gl->glBindTexture(GL_TEXTURE_BUFFER, m_pointTexture);
        gl->glBindVertexArray(m_vao);
        if (elementBuffer != m_indexBuffer)
            gl->glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, elementBuffer); // VAO state: put back below
        gl->glEnable(GL_PRIMITIVE_RESTART);
        gl->glPrimitiveRestartIndex(HairStripLayout::kRestart);
        gl->glDrawElements(lines ? GL_LINE_STRIP : GL_TRIANGLE_STRIP, indexCount, GL_UNSIGNED_INT,
            reinterpret_cast<const void*>(byteOffset));
        gl->glDisable(GL_PRIMITIVE_RESTART);
        if (elementBuffer != m_indexBuffer)
            gl->glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m_indexBuffer);
        gl->glBindVertexArray(0);
        gl->glBindTexture(GL_TEXTURE_BUFFER, 0);
        gl->glActiveTexture(GL_TEXTURE1);
        gl->glBindTexture(GL_TEXTURE_BUFFER, 0);
        gl->glActiveTexture(GL_TEXTURE0);
        unbindShadowLookup(gl);
        program.release();
    }

    gl->glDisable(GL_BLEND);
    gl->glDepthMask(GL_TRUE);
    m_lastDrawnStrands = drawn;
    m_lastDrewLines = lines;
    m_lastDrewTwoPasses = drawnInTwoPasses;
    m_lastSamplesPerSegment
        = static_cast<int>(HairStripLayout::kSamplesPerSegment / HairStripLayout::kSampleSteps[stepIndex]);
    checkGlErrors(gl, "HairRenderer::draw");
}

bool HairRenderer::captureWithProgram(QOpenGLShaderProgram& program, const DrawPlan& plan, const RenderView& view,
    const HairStyle& style, GLuint buffer, std::size_t bytesPerSample, std::size_t& capacity)
{
    const HairStripLayout::IndexList& list = *plan.centreLine;
    const std::size_t indexCount = list.prefix[plan.drawn];
    // One restart ends each strand's strip; a point is captured for each other index, in order.
    const std::size_t samples = indexCount - plan.drawn;
    if (samples == 0 || samples > static_cast<std::size_t>(std::numeric_limits<GLsizeiptr>::max()) / bytesPerSample)
        return false;
    GlFunctions* gl = m_gl;
    const auto bytes = static_cast<GLsizeiptr>(samples * bytesPerSample);
    if (samples > capacity) {
        gl->glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, buffer);
        gl->glBufferData(GL_TRANSFORM_FEEDBACK_BUFFER, bytes, nullptr, GL_STREAM_READ);
        gl->glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, 0);
        capacity = samples;
    }
    setStrandUniforms(program, view, style, plan.widthScale, plan.lines);
    bindStrandTextures();
    gl->glEnable(GL_RASTERIZER_DISCARD);
    gl->glBindBufferRange(GL_TRANSFORM_FEEDBACK_BUFFER, 0, buffer, 0, bytes);
    gl->glBindVertexArray(m_vao);
    if (plan.elementBuffer != m_indexBuffer)
        gl->glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, plan.elementBuffer); // VAO state: put back below
    gl->glEnable(GL_PRIMITIVE_RESTART);
    gl->glPrimitiveRestartIndex(HairStripLayout::kRestart);
    gl->glBeginTransformFeedback(GL_POINTS);
    gl->glDrawElements(GL_POINTS, static_cast<GLsizei>(indexCount), GL_UNSIGNED_INT,
        reinterpret_cast<const void*>(plan.centreLineByteOffset));
    gl->glEndTransformFeedback();
    gl->glDisable(GL_PRIMITIVE_RESTART);
    if (plan.elementBuffer != m_indexBuffer)
        gl->glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m_indexBuffer);
    gl->glBindVertexArray(0);
    gl->glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
    gl->glDisable(GL_RASTERIZER_DISCARD);
    unbindStrandTextures();
    unbindShadowLookup(gl);
    program.release();
    checkGlErrors(gl, "HairRenderer::captureWithProgram");
    return true;
}

void HairRenderer::bindStrandTextures()
{
    m_gl->glActiveTexture(GL_TEXTURE1);
    m_gl->glBindTexture(GL_TEXTURE_BUFFER, m_lookTexture);
    m_gl->glActiveTexture(GL_TEXTURE0);
    m_gl->glBindTexture(GL_TEXTURE_BUFFER, m_pointTexture);
}

void HairRenderer::unbindStrandTextures()
{
    m_gl->glBindTexture(GL_TEXTURE_BUFFER, 0);
    m_gl->glActiveTexture(GL_TEXTURE1);
    m_gl->glBindTexture(GL_TEXTURE_BUFFER, 0);
    m_gl->glActiveTexture(GL_TEXTURE0);
}

HairShadingView HairRenderer::shadingView(const RenderView& view, const HairStyle& style, const DrawPlan& plan) const
{
    // What setStrandUniforms gives the shaders.
    HairShadingView shading;
    shading.view = view.view;
    shading.projection = view.projection;
    shading.viewportPixels = view.viewportPixels;
    shading.ribbon = !plan.lines;
    shading.widthScale = style.lockWidthScale * plan.widthScale;
    shading.tipThicknessRatio = std::clamp(style.tipThicknessRatio, 0.0f, 1.0f);
    shading.minWidthPixels = std::max(style.minWidthPixels, 0.01f);
    shading.tipFade = std::clamp(style.tipFade, 0.0f, 1.0f);
    shading.shadows = view.shadow.enabled;
    shading.keyLightView = view.keyLightView;
    shading.fillLightView = view.fillLightView;
    shading.headCentreView = view.headCentreView;
    return shading;
}

bool HairRenderer::prepareSoftware(const RenderView& view, const HairStyle& style, float fraction, bool coarse)
{
    m_softwareSamples = 0;
    m_lastDrawnStrands = 0;
    if (!m_worldProgram || m_vertexCount == 0 || m_layout.drawnStrands == 0)
        return false;
    const DrawPlan plan = planDraw(view, style, fraction, coarse);
    const HairStripLayout::IndexList& list = *plan.centreLine;
    const std::size_t drawn = plan.drawn;
    const std::size_t samples = list.prefix[drawn] - drawn;
    // What the world capture depends on; a paused orbit keeps all of it.
    const WorldKey key{ m_worldRevision, plan.centreLine, drawn, view.shadow, linearFromSrgb(style.rootColour),
        linearFromSrgb(style.tipColour), style.hairThicknessMetres };
    if (!m_worldKey || !(*m_worldKey == key)) {
        m_worldKey.reset();
        if (!captureWithProgram(
                *m_worldProgram, plan, view, style, m_worldBuffer, sizeof(HairWorldSample), m_worldCapacity))
            return false;
        m_worldKey = key;
        ++m_worldCaptures;
        m_softwareStrandEnds.resize(drawn);
        for (std::size_t s = 0; s < drawn; ++s)
            m_softwareStrandEnds[s] = list.prefix[s + 1] - static_cast<std::uint32_t>(s + 1);
    }
    m_softwareSamples = samples;
    m_softwareView = shadingView(view, style, plan);
    m_lastDrawnStrands = drawn;
    m_lastDrewLines = plan.lines;
    m_lastDrewTwoPasses = false;
    m_lastDrawnLineSegments = plan.lines ? samples - drawn : 0;
    m_lastSamplesPerSegment
        = static_cast<int>(HairStripLayout::kSamplesPerSegment / HairStripLayout::kSampleSteps[plan.stepIndex]);
    return true;
}

bool HairRenderer::withWorldSamples(const std::function<void(std::span<const HairWorldSample>)>& use)
{
    if (m_softwareSamples == 0 || !m_gl)
        return false;
    GlFunctions* gl = m_gl;
    const auto bytes = static_cast<GLsizeiptr>(m_softwareSamples * sizeof(HairWorldSample));
    gl->glBindBuffer(GL_COPY_READ_BUFFER, m_worldBuffer);
    const void* mapped = gl->glMapBufferRange(GL_COPY_READ_BUFFER, 0, bytes, GL_MAP_READ_BIT);
    if (mapped) {
        use({ static_cast<const HairWorldSample*>(mapped), m_softwareSamples });
        gl->glUnmapBuffer(GL_COPY_READ_BUFFER);
    }
    gl->glBindBuffer(GL_COPY_READ_BUFFER, 0);
    checkGlErrors(gl, "HairRenderer::withWorldSamples");
    return mapped != nullptr;
}

std::span<const std::uint8_t> HairRenderer::drawSoftware(
    const PixelRect& region, std::span<const float> depth, ThreadPool* pool)
{
    m_shaded.resize(m_softwareSamples);
    if (!withWorldSamples(
            [&](std::span<const HairWorldSample> world) { shadeHairSamples(world, m_softwareView, m_shaded, pool); }))
        return {};
    HairRasterInput input;
    input.samples = m_shaded;
    input.strandEnds = m_softwareStrandEnds;
    input.width = static_cast<int>(std::lround(m_softwareView.viewportPixels.x));
    input.height = static_cast<int>(std::lround(m_softwareView.viewportPixels.y));
    input.region = region;
    input.depth = depth;
    return m_raster.draw(input, pool);
}

std::vector<HairRasterSample> HairRenderer::shadedSamples(
    const RenderView& view, const HairStyle& style, float fraction, bool coarse, bool onCpu)
{
    std::vector<HairRasterSample> result;
    if (onCpu) {
        if (prepareSoftware(view, style, fraction, coarse)) {
            result.resize(m_softwareSamples);
            withWorldSamples(
                [&](std::span<const HairWorldSample> world) { shadeHairSamples(world, m_softwareView, result); });
        }
        return result;
    }
    if (!m_sampleProgram || m_vertexCount == 0 || m_layout.drawnStrands == 0)
        return result;
    const DrawPlan plan = planDraw(view, style, fraction, coarse);
    const std::size_t samples = plan.centreLine->prefix[plan.drawn] - plan.drawn;
    if (!captureWithProgram(
            *m_sampleProgram, plan, view, style, m_captureBuffer, sizeof(HairRasterSample), m_captureCapacity))
        return result;
    GlFunctions* gl = m_gl;
    gl->glBindBuffer(GL_COPY_READ_BUFFER, m_captureBuffer);
    const auto* mapped = static_cast<const HairRasterSample*>(gl->glMapBufferRange(
        GL_COPY_READ_BUFFER, 0, static_cast<GLsizeiptr>(samples * sizeof(HairRasterSample)), GL_MAP_READ_BIT));
    if (mapped) {
        result.assign(mapped, mapped + samples);
        gl->glUnmapBuffer(GL_COPY_READ_BUFFER);
    }
    gl->glBindBuffer(GL_COPY_READ_BUFFER, 0);
    return result;
}

void HairRenderer::rebuildDecimatedLines(float toleranceMetres)
{
    m_decimatedLines = decimatedLines(m_layout, m_chordDeviations, toleranceMetres);
    ++m_worldRevision;
    if (m_decimatedLines.prefix.size() != m_layout.drawnStrands + 1) {
        m_decimatedToleranceMetres = -1.0f;
        return;
    }
    // Through the copy target: the element array binding belongs to whichever VAO is bound.
    m_gl->glBindBuffer(GL_COPY_WRITE_BUFFER, m_decimatedIndexBuffer);
    m_gl->glBufferData(GL_COPY_WRITE_BUFFER,
        static_cast<GLsizeiptr>(m_decimatedLines.indices.size() * sizeof(std::uint32_t)),
        m_decimatedLines.indices.data(), GL_STATIC_DRAW);
    m_gl->glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
    m_decimatedToleranceMetres = toleranceMetres;
    checkGlErrors(m_gl, "HairRenderer::rebuildDecimatedLines");
}

HairRenderer::DrawnShare HairRenderer::drawnShare(float fraction) const
{
    const std::size_t total = m_layout.drawnStrands;
    if (total == 0)
        return {};
    const float wanted = std::isfinite(fraction) ? std::clamp(fraction, 0.0f, 1.0f) : 1.0f;
    const std::size_t drawn = std::clamp<std::size_t>(static_cast<std::size_t>(std::lround(wanted * total)), 1, total);
    // Each drawn strand stands for total / drawn strands and is widened by as much, so a preview
    // (or a display density below 1) covers the head as the whole hair does: the same coverage,
    // never a balding subset (issue 14; the square root used before left 13-17 % of the strands
    // covering about half of what the whole hair covers).
    return { drawn, static_cast<float>(total) / static_cast<float>(drawn) };
}

Aabb HairRenderer::drawnBounds(const HairStyle& style, float fraction) const
{
    const float thickest = std::max(style.hairThicknessMetres, m_thickestLookMetres);
    const float halfWidth = 0.5f * thickest * std::max(style.lockWidthScale, 0.0f) * drawnShare(fraction).widthScale;
    // A Catmull-Rom segment leaves its points' box by at most 4/27 of its two end tangents, each
    // at most a segment long (the Hermite basis h10 peaks at 4/27): 0.3 of the longest segment.
    const float reach = (std::isfinite(halfWidth) ? halfWidth : 0.0f) + 0.3f * m_longestSegmentMetres;
    return Aabb{ m_bounds.min - glm::vec3(reach), m_bounds.max + glm::vec3(reach) };
}

void HairRenderer::setStrandUniforms(
    QOpenGLShaderProgram& program, const RenderView& view, const HairStyle& style, float widthScale, bool lines) const
{
    GlFunctions* gl = m_gl;
    program.bind();
    setUniform(program, "u_view", view.view);
    setUniform(program, "u_projection", view.projection);
    setUniform(program, "u_viewportPixels", view.viewportPixels);
    setUniform(program, "u_samplesPerSegment", static_cast<float>(HairStripLayout::kSamplesPerSegment));
    setUniform(program, "u_ribbon", lines ? 0.0f : 1.0f);
    setUniform(program, "u_hairThicknessMetres", style.hairThicknessMetres);
    setUniform(program, "u_widthScale", style.lockWidthScale * widthScale);
    setUniform(program, "u_tipThicknessRatio", std::clamp(style.tipThicknessRatio, 0.0f, 1.0f));
    setUniform(program, "u_minWidthPixels", std::max(style.minWidthPixels, 0.01f));
    setUniform(program, "u_rootColour", linearFromSrgb(style.rootColour));
    setUniform(program, "u_tipColour", linearFromSrgb(style.tipColour));
    setUniform(program, "u_keyLightView", view.keyLightView);
    setUniform(program, "u_fillLightView", view.fillLightView);
    setUniform(program, "u_headCentreView", view.headCentreView);
    setUniform(program, "u_tipFade", std::clamp(style.tipFade, 0.0f, 1.0f));
    bindShadowLookup(gl, program, view.shadow);
}

bool HairRenderer::drawRibbonsFromSamples(std::size_t samples, GLsizei indexCount, std::size_t byteOffset)
{
    GlFunctions* gl = m_gl;
    if (samples == 0 || 3 * samples > static_cast<std::size_t>(m_maxTexels)) {
        unbindShadowLookup(gl);
        m_sampleProgram->release();
        return false;
    }
    constexpr std::size_t kSampleBytes = 3 * sizeof(glm::vec4);
    if (samples > m_sampleCapacity) {
        gl->glBindBuffer(GL_TEXTURE_BUFFER, m_sampleBuffer);
        gl->glBufferData(GL_TEXTURE_BUFFER, static_cast<GLsizeiptr>(samples * kSampleBytes), nullptr, GL_STREAM_COPY);
        m_sampleCapacity = samples;
        gl->glBindTexture(GL_TEXTURE_BUFFER, m_sampleTexture);
        gl->glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, m_sampleBuffer);
        gl->glBindTexture(GL_TEXTURE_BUFFER, 0);
        gl->glBindBuffer(GL_TEXTURE_BUFFER, 0);
    }
    // Pass 1 (m_sampleProgram is bound with its uniforms): every sample once, nothing rasterised.
    bindStrandTextures();
    gl->glEnable(GL_RASTERIZER_DISCARD);
    gl->glBindBufferRange(
        GL_TRANSFORM_FEEDBACK_BUFFER, 0, m_sampleBuffer, 0, static_cast<GLsizeiptr>(samples * kSampleBytes));
    gl->glBindVertexArray(m_sampleVao);
    gl->glBeginTransformFeedback(GL_POINTS);
    gl->glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(samples));
    gl->glEndTransformFeedback();
    gl->glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
    gl->glDisable(GL_RASTERIZER_DISCARD);
    unbindStrandTextures();
    unbindShadowLookup(gl);
    m_sampleProgram->release();

    // Pass 2: both edges of every sample, from the captured samples (unit 0).
    m_ribbonProgram->bind();
    gl->glBindTexture(GL_TEXTURE_BUFFER, m_sampleTexture);
    gl->glBindVertexArray(m_vao); // its element buffer: the same ribbon strips
    gl->glEnable(GL_PRIMITIVE_RESTART);
    gl->glPrimitiveRestartIndex(HairStripLayout::kRestart);
    gl->glDrawElements(GL_TRIANGLE_STRIP, indexCount, GL_UNSIGNED_INT, reinterpret_cast<const void*>(byteOffset));
    gl->glDisable(GL_PRIMITIVE_RESTART);
    gl->glBindVertexArray(0);
    gl->glBindTexture(GL_TEXTURE_BUFFER, 0);
    m_ribbonProgram->release();
    return true;
}

void HairRenderer::drawPoints(QOpenGLShaderProgram&)
{
    if (!m_program || m_vertexCount == 0 || m_layout.drawnStrands == 0)
        return;
    GlFunctions* gl = m_gl;
    constexpr std::size_t kCoarse = 2; // HairStripLayout::kSampleSteps[2]: the points themselves
    gl->glActiveTexture(GL_TEXTURE0);
    gl->glBindTexture(GL_TEXTURE_BUFFER, m_pointTexture);
    gl->glBindVertexArray(m_vao);
    gl->glEnable(GL_PRIMITIVE_RESTART);
    gl->glPrimitiveRestartIndex(HairStripLayout::kRestart);
    const HairStripLayout::IndexList& list = m_layout.indices(HairStripLayout::Primitive::Lines, kCoarse);
    gl->glDrawElements(GL_LINE_STRIP, static_cast<GLsizei>(list.prefix[m_layout.drawnStrands]), GL_UNSIGNED_INT,
        reinterpret_cast<const void*>(m_indexOffsets[0][kCoarse]));
    gl->glDisable(GL_PRIMITIVE_RESTART);
    gl->glBindVertexArray(0);
    gl->glBindTexture(GL_TEXTURE_BUFFER, 0);
    checkGlErrors(gl, "HairRenderer::drawPoints");
}

} // namespace wisp
