#include "widgets/HeadRenderer.h"

#include "widgets/HairShadowMap.h"

#include <QOpenGLShaderProgram>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>

#include <glm/common.hpp>
#include <glm/vec2.hpp>

namespace wisp {

HeadRenderer::~HeadRenderer() = default;

bool HeadRenderer::initialize(GlFunctions* gl)
{
    m_gl = gl;
    m_program = loadShaderProgram(QStringLiteral("head"), &m_error);
    if (!m_program)
        return false;
    QString lightError;
    m_lightProgram = loadTransformFeedbackProgram(gl, QStringLiteral("head_light"), { "t_light" }, &lightError);
    if (!m_lightProgram)
        qWarning("HeadRenderer: the head is drawn without the hair's shadow: %s", qPrintable(lightError));
    gl->glGenVertexArrays(1, &m_vao);
    gl->glGenBuffers(1, &m_vertexBuffer);
    gl->glGenBuffers(1, &m_weightBuffer);
    gl->glGenBuffers(1, &m_coverageBuffer);
    gl->glGenBuffers(1, &m_indexBuffer);
    gl->glGenBuffers(1, &m_lightBuffer);
    // Attributes 0 and 1, positions and normals, of the bound vertex array: both arrays read them.
    const auto positionsAndNormals = [&] {
        gl->glBindBuffer(GL_ARRAY_BUFFER, m_vertexBuffer);
        gl->glEnableVertexAttribArray(0);
        gl->glVertexAttribPointer(
            0, 3, GL_FLOAT, GL_FALSE, sizeof(Vertex), reinterpret_cast<const void*>(offsetof(Vertex, position)));
        gl->glEnableVertexAttribArray(1);
        gl->glVertexAttribPointer(
            1, 3, GL_FLOAT, GL_FALSE, sizeof(Vertex), reinterpret_cast<const void*>(offsetof(Vertex, normal)));
    };
    gl->glBindVertexArray(m_vao);
    gl->glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m_indexBuffer); // recorded in the VAO
    positionsAndNormals();
    gl->glBindBuffer(GL_ARRAY_BUFFER, m_weightBuffer);
    gl->glEnableVertexAttribArray(2);
    gl->glVertexAttribPointer(2, 1, GL_FLOAT, GL_FALSE, sizeof(float), nullptr);
    gl->glBindBuffer(GL_ARRAY_BUFFER, m_coverageBuffer);
    gl->glEnableVertexAttribArray(3);
    gl->glVertexAttribPointer(3, 4, GL_FLOAT, GL_FALSE, sizeof(glm::vec4), nullptr);
    gl->glBindBuffer(GL_ARRAY_BUFFER, m_lightBuffer);
    gl->glEnableVertexAttribArray(4);
    gl->glVertexAttribPointer(4, 2, GL_FLOAT, GL_FALSE, sizeof(glm::vec2), nullptr);
    gl->glGenVertexArrays(1, &m_lightVao);
    gl->glBindVertexArray(m_lightVao);
    positionsAndNormals();
    gl->glBindVertexArray(0);
    gl->glBindBuffer(GL_ARRAY_BUFFER, 0);
    m_indexCount = 0;
    m_dirty = !m_triangles.empty();
    checkGlErrors(gl, "HeadRenderer::initialize");
    return true;
}

void HeadRenderer::release()
{
    if (!m_gl)
        return;
    m_gl->glDeleteBuffers(1, &m_indexBuffer);
    m_gl->glDeleteBuffers(1, &m_lightBuffer);
    m_lightBuffer = 0;
    m_lightKey.reset();
    m_lightProgram.reset();
    m_gl->glDeleteVertexArrays(1, &m_lightVao);
    m_lightVao = 0;
    m_gl->glDeleteBuffers(1, &m_weightBuffer);
    m_gl->glDeleteBuffers(1, &m_coverageBuffer);
    m_coverageBuffer = 0;
    m_gl->glDeleteBuffers(1, &m_vertexBuffer);
    m_gl->glDeleteVertexArrays(1, &m_vao);
    m_indexBuffer = m_weightBuffer = m_vertexBuffer = m_vao = 0;
    m_indexCount = 0;
    m_program.reset();
    m_gl = nullptr;
}

void HeadRenderer::setMesh(const TriangleMesh& mesh)
{
    m_vertices.clear();
    m_triangles.clear();
    m_dirty = true;
    if (!validateMesh(mesh).empty())
        return;
    const std::vector<glm::vec3> normals = vertexNormals(mesh);
    m_vertices.resize(mesh.positions.size());
    for (std::size_t i = 0; i < mesh.positions.size(); ++i)
        m_vertices[i] = { mesh.positions[i], normals[i] };
    m_triangles = mesh.triangles;
}

void HeadRenderer::setGrowthWeights(std::vector<float> weights)
{
    // Sanitised once here rather than per fragment: a NaN would survive the shader's clamp.
    for (float& w : weights)
        w = std::isfinite(w) ? std::clamp(w, 0.0f, 1.0f) : 0.0f;
    m_weights = std::move(weights);
    m_weightsDirty = true;
}

void HeadRenderer::uploadPending()
{
    m_dirty = false;
    m_gl->glBindBuffer(GL_ARRAY_BUFFER, m_vertexBuffer);
    m_gl->glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(m_vertices.size() * sizeof(Vertex)), m_vertices.data(),
        GL_STATIC_DRAW);
    // Storage for the weights, filled by uploadWeights (the attribute is read even while the
    // overlay is off; the shader then ignores its value).
    m_gl->glBindBuffer(GL_ARRAY_BUFFER, m_weightBuffer);
    m_gl->glBufferData(
        GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(m_vertices.size() * sizeof(float)), nullptr, GL_DYNAMIC_DRAW);
    m_weightsDirty = true;
    m_gl->glBindBuffer(GL_ARRAY_BUFFER, m_coverageBuffer);
    m_gl->glBufferData(
        GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(m_vertices.size() * sizeof(glm::vec4)), nullptr, GL_DYNAMIC_DRAW);
    m_coverageDirty = true;
    // Fully lit until updateLight() looks the shadows up (and for good, without its program).
    const std::vector<glm::vec2> lit(m_vertices.size(), glm::vec2(1.0f));
    m_gl->glBindBuffer(GL_ARRAY_BUFFER, m_lightBuffer);
    m_gl->glBufferData(
        GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(lit.size() * sizeof(glm::vec2)), lit.data(), GL_DYNAMIC_COPY);
    m_lightKey.reset();
    m_gl->glBindBuffer(GL_ARRAY_BUFFER, 0);
    // The element buffer binding is VAO state: bind the VAO to touch it.
    m_gl->glBindVertexArray(m_vao);
    m_gl->glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(m_triangles.size() * sizeof(glm::uvec3)),
        m_triangles.data(), GL_STATIC_DRAW);
    m_gl->glBindVertexArray(0);
    m_indexCount = static_cast<GLsizei>(m_triangles.size() * 3);
    checkGlErrors(m_gl, "HeadRenderer::uploadPending");
}

void HeadRenderer::setScalpCoverage(std::vector<glm::vec4> coverage)
{
    m_coverage = std::move(coverage);
    m_coverageDirty = true;
}

void HeadRenderer::uploadCoverage()
{
    m_coverageDirty = false;
    // Linear colours for the shader; zero weight where the count does not match the mesh.
    std::vector<glm::vec4> linear(m_vertices.size(), glm::vec4(0.0f));
    if (m_coverage.size() == m_vertices.size())
        for (std::size_t i = 0; i < linear.size(); ++i) {
            const glm::vec4& c = m_coverage[i];
            const float w = std::isfinite(c.w) ? std::clamp(c.w, 0.0f, 1.0f) : 0.0f;
            linear[i] = glm::vec4(linearFromSrgb(glm::clamp(glm::vec3(c), 0.0f, 1.0f)), w);
        }
    m_gl->glBindBuffer(GL_ARRAY_BUFFER, m_coverageBuffer);
    m_gl->glBufferSubData(
        GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(linear.size() * sizeof(glm::vec4)), linear.data());
    m_gl->glBindBuffer(GL_ARRAY_BUFFER, 0);
    checkGlErrors(m_gl, "HeadRenderer::uploadCoverage");
}

void HeadRenderer::uploadWeights()
{
    m_weightsDirty = false;
    if (!hasGrowthOverlay())
        return;
    // The buffer was sized for this mesh in uploadPending, and the weights match the mesh.
    m_gl->glBindBuffer(GL_ARRAY_BUFFER, m_weightBuffer);
    m_gl->glBufferSubData(
        GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(m_weights.size() * sizeof(float)), m_weights.data());
    m_gl->glBindBuffer(GL_ARRAY_BUFFER, 0);
    checkGlErrors(m_gl, "HeadRenderer::uploadWeights");
}

void HeadRenderer::updateLight(const ShadowLookup& shadow, const glm::mat4& modelToWorld)
{
    if (!m_lightProgram || m_vertices.empty())
        return;
    if (m_lightKey && m_lightKey->shadow.sameAs(shadow) && m_lightKey->modelToWorld == modelToWorld)
        return;
    GlFunctions* gl = m_gl;
    QOpenGLShaderProgram& program = *m_lightProgram;
    program.bind();
    setUniform(program, "u_modelToWorld", modelToWorld);
    bindShadowLookup(gl, program, shadow);
    gl->glEnable(GL_RASTERIZER_DISCARD);
    gl->glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, m_lightBuffer);
    gl->glBindVertexArray(m_lightVao);
    gl->glBeginTransformFeedback(GL_POINTS);
    gl->glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(m_vertices.size()));
    gl->glEndTransformFeedback();
    gl->glBindVertexArray(0);
    gl->glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
    gl->glDisable(GL_RASTERIZER_DISCARD);
    unbindShadowLookup(gl);
    program.release();
    m_lightKey = LightKey{ shadow, modelToWorld };
    ++m_lightUpdates;
    checkGlErrors(gl, "HeadRenderer::updateLight");
}

void HeadRenderer::draw(const RenderView& view, bool showGrowthOverlay)
{
    if (!m_program)
        return;
    if (m_dirty)
        uploadPending();
    if (m_weightsDirty)
        uploadWeights();
    if (m_coverageDirty && !m_vertices.empty())
        uploadCoverage();
    if (m_indexCount == 0)
        return;
    updateLight(view.shadow, view.modelToWorld);

    GlFunctions* gl = m_gl;
    gl->glEnable(GL_DEPTH_TEST);
    gl->glDepthMask(GL_TRUE);
    gl->glDisable(GL_BLEND);
    // The mesh is closed and wound counter-clockwise seen from outside.
    gl->glEnable(GL_CULL_FACE);
    gl->glCullFace(GL_BACK);
    gl->glFrontFace(GL_CCW);

    QOpenGLShaderProgram& program = *m_program;
    program.bind();
    setUniform(program, "u_view", view.view);
    setUniform(program, "u_viewProjection", view.viewProjection);
    setUniform(program, "u_skinColour", linearFromSrgb(m_colourSrgb));
    setUniform(program, "u_keyLightView", view.keyLightView);
    setUniform(program, "u_fillLightView", view.fillLightView);
    setUniform(program, "u_growthOverlay", showGrowthOverlay && hasGrowthOverlay() ? 1.0f : 0.0f);
    gl->glBindVertexArray(m_vao);
    gl->glDrawElements(GL_TRIANGLES, m_indexCount, GL_UNSIGNED_INT, nullptr);
    gl->glBindVertexArray(0);
    program.release();
    gl->glDisable(GL_CULL_FACE);
    checkGlErrors(gl, "HeadRenderer::draw");
}

void HeadRenderer::drawWith(QOpenGLShaderProgram&)
{
    if (!m_program)
        return;
    if (m_dirty)
        uploadPending();
    if (m_indexCount == 0)
        return;
    // Both faces: a shadow map wants the nearest surface whichever way it faces.
    m_gl->glBindVertexArray(m_vao);
    m_gl->glDrawElements(GL_TRIANGLES, m_indexCount, GL_UNSIGNED_INT, nullptr);
    m_gl->glBindVertexArray(0);
    checkGlErrors(m_gl, "HeadRenderer::drawWith");
}

} // namespace wisp
