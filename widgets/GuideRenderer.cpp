#include "widgets/GuideRenderer.h"

#include <QOpenGLShaderProgram>

#include <cstddef>
#include <utility>

namespace wisp {

GuideRenderer::~GuideRenderer() = default;

bool GuideRenderer::initialize(GlFunctions* gl)
{
    m_gl = gl;
    m_program = loadShaderProgram(QStringLiteral("guide"), &m_error);
    if (!m_program)
        return false;
    createMesh(m_gridMesh);
    createMesh(m_arrowMesh);
    createMesh(m_brushMesh);
    // A new context has none of the old buffers' contents.
    m_gridMesh.dirty = m_arrowMesh.dirty = m_brushMesh.dirty = true;
    checkGlErrors(gl, "GuideRenderer::initialize");
    return true;
}

void GuideRenderer::createMesh(Mesh& mesh)
{
    GlFunctions* gl = m_gl;
    gl->glGenVertexArrays(1, &mesh.vao);
    gl->glGenBuffers(1, &mesh.buffer);
    gl->glBindVertexArray(mesh.vao);
    gl->glBindBuffer(GL_ARRAY_BUFFER, mesh.buffer);
    gl->glEnableVertexAttribArray(0);
    gl->glVertexAttribPointer(
        0, 3, GL_FLOAT, GL_FALSE, sizeof(GuideVertex), reinterpret_cast<const void*>(offsetof(GuideVertex, position)));
    gl->glEnableVertexAttribArray(1);
    gl->glVertexAttribPointer(
        1, 3, GL_FLOAT, GL_FALSE, sizeof(GuideVertex), reinterpret_cast<const void*>(offsetof(GuideVertex, normal)));
    gl->glEnableVertexAttribArray(2);
    gl->glVertexAttribPointer(
        2, 4, GL_FLOAT, GL_FALSE, sizeof(GuideVertex), reinterpret_cast<const void*>(offsetof(GuideVertex, colour)));
    gl->glBindVertexArray(0);
    gl->glBindBuffer(GL_ARRAY_BUFFER, 0);
    mesh.count = 0;
}

void GuideRenderer::release()
{
    if (!m_gl)
        return;
    for (Mesh* mesh : { &m_gridMesh, &m_arrowMesh, &m_brushMesh }) {
        m_gl->glDeleteBuffers(1, &mesh->buffer);
        m_gl->glDeleteVertexArrays(1, &mesh->vao);
        mesh->buffer = mesh->vao = 0;
        mesh->count = 0;
    }
    m_program.reset();
    m_gl = nullptr;
}

void GuideRenderer::setGrid(GroundGrid grid)
{
    m_grid = std::move(grid);
    m_gridMesh.dirty = true;
}

void GuideRenderer::setWindArrow(WindArrow arrow)
{
    m_arrow = std::move(arrow);
    m_arrowMesh.dirty = true;
}

void GuideRenderer::setBrushRings(std::vector<GuideVertex> triangles)
{
    m_brushRings = std::move(triangles);
    m_brushMesh.dirty = true;
}

void GuideRenderer::upload(Mesh& mesh, const std::vector<GuideVertex>& vertices)
{
    mesh.dirty = false;
    m_gl->glBindBuffer(GL_ARRAY_BUFFER, mesh.buffer);
    m_gl->glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(GuideVertex)), vertices.data(),
        GL_DYNAMIC_DRAW);
    m_gl->glBindBuffer(GL_ARRAY_BUFFER, 0);
    mesh.count = static_cast<GLsizei>(vertices.size());
}

void GuideRenderer::bindProgram(const RenderView& view, float lit, float fadeRadius)
{
    QOpenGLShaderProgram& program = *m_program;
    program.bind();
    setUniform(program, "u_view", view.view);
    setUniform(program, "u_viewProjection", view.viewProjection);
    setUniform(program, "u_keyLightView", view.keyLightView);
    setUniform(program, "u_lit", lit);
    setUniform(program, "u_fadeCentre", m_grid.centre);
    setUniform(program, "u_fadeRadius", fadeRadius);
    setUniform(program, "u_alphaScale", 1.0f);
}

void GuideRenderer::drawWindArrow(const RenderView& view)
{
    if (!m_program)
        return;
    if (m_arrowMesh.dirty)
        upload(m_arrowMesh, m_arrow.visible ? m_arrow.triangles : std::vector<GuideVertex>{});
    if (m_arrowMesh.count == 0)
        return;
    m_gl->glEnable(GL_DEPTH_TEST);
    m_gl->glDepthMask(GL_TRUE);
    m_gl->glDisable(GL_BLEND);
    bindProgram(view, 1.0f, 0.0f);
    m_gl->glBindVertexArray(m_arrowMesh.vao);
    m_gl->glDrawArrays(GL_TRIANGLES, 0, m_arrowMesh.count);
    m_gl->glBindVertexArray(0);
    m_program->release();
    checkGlErrors(m_gl, "GuideRenderer::drawWindArrow");
}

void GuideRenderer::drawGrid(const RenderView& view)
{
    if (!m_program)
        return;
    if (m_gridMesh.dirty)
        upload(m_gridMesh, m_grid.lines);
    if (m_gridMesh.count == 0)
        return;
    // Tested against the depth of what is drawn, but writing none: the grid is a translucent
    // overlay, which hides nothing drawn after it (the viewport draws the hair after it).
    m_gl->glEnable(GL_DEPTH_TEST);
    m_gl->glDepthMask(GL_FALSE);
    m_gl->glEnable(GL_BLEND);
    m_gl->glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    bindProgram(view, 0.0f, m_grid.fadeRadiusMetres);
    m_gl->glBindVertexArray(m_gridMesh.vao);
    m_gl->glDrawArrays(GL_LINES, 0, m_gridMesh.count);
    m_gl->glBindVertexArray(0);
    m_program->release();
    m_gl->glDepthMask(GL_TRUE);
    m_gl->glDisable(GL_BLEND);
    checkGlErrors(m_gl, "GuideRenderer::drawGrid");
}

void GuideRenderer::drawBrushPass(GLsizei count, float alphaScale)
{
    setUniform(*m_program, "u_alphaScale", alphaScale);
    m_gl->glDrawArrays(GL_TRIANGLES, 0, count);
}

void GuideRenderer::drawBrushRings(const RenderView& view)
{
    if (!m_program)
        return;
    if (m_brushMesh.dirty)
        upload(m_brushMesh, m_brushRings);
    if (m_brushMesh.count == 0)
        return;
    GlFunctions* gl = m_gl;
    gl->glDepthMask(GL_FALSE); // an overlay: nothing drawn later should be hidden by it
    gl->glEnable(GL_BLEND);
    gl->glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    gl->glDisable(GL_CULL_FACE); // seen from either side
    bindProgram(view, 0.0f, 0.0f);
    gl->glBindVertexArray(m_brushMesh.vao);

    // Hidden parts: faint, whatever is in front.
    gl->glDisable(GL_DEPTH_TEST);
    drawBrushPass(m_brushMesh.count, 0.3f);
    // Visible parts: full strength. The ring is lifted off the surface, but where the scalp curves
    // away under its flat circle, or at grazing angles, depth precision alone would let the skin
    // win; the polygon offset pulls the ring a few depth steps toward the camera.
    gl->glEnable(GL_DEPTH_TEST);
    gl->glDepthFunc(GL_LEQUAL);
    gl->glEnable(GL_POLYGON_OFFSET_FILL);
    gl->glPolygonOffset(-1.0f, -4.0f);
    drawBrushPass(m_brushMesh.count, 1.0f);
    gl->glDisable(GL_POLYGON_OFFSET_FILL);
    gl->glDepthFunc(GL_LESS);

    gl->glBindVertexArray(0);
    m_program->release();
    gl->glDepthMask(GL_TRUE);
    gl->glDisable(GL_BLEND);
    checkGlErrors(gl, "GuideRenderer::drawBrushRings");
}

} // namespace wisp
