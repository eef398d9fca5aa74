#include "widgets/BackgroundRenderer.h"

#include <QOpenGLShaderProgram>

namespace wisp {

BackgroundRenderer::~BackgroundRenderer() = default;

bool BackgroundRenderer::initialize(GlFunctions* gl)
{
    m_gl = gl;
    m_program = loadShaderProgram(QStringLiteral("background"), &m_error);
    if (!m_program)
        return false;
    gl->glGenVertexArrays(1, &m_vao);
    return true;
}

void BackgroundRenderer::release()
{
    if (!m_gl)
        return;
    m_gl->glDeleteVertexArrays(1, &m_vao);
    m_vao = 0;
    m_program.reset();
    m_gl = nullptr;
}

void BackgroundRenderer::draw(const glm::vec3& topSrgb, const glm::vec3& bottomSrgb)
{
    if (!m_program)
        return;
    m_gl->glDisable(GL_DEPTH_TEST);
    m_gl->glDepthMask(GL_FALSE);
    m_gl->glDisable(GL_BLEND);
    m_program->bind();
    setUniform(*m_program, "u_top", topSrgb);
    setUniform(*m_program, "u_bottom", bottomSrgb);
    m_gl->glBindVertexArray(m_vao);
    m_gl->glDrawArrays(GL_TRIANGLES, 0, 3);
    m_gl->glBindVertexArray(0);
    m_program->release();
    m_gl->glDepthMask(GL_TRUE);
    checkGlErrors(m_gl, "BackgroundRenderer::draw");
}

} // namespace wisp
