#pragma once
// Fills the view with the viewport's background: a vertical gradient.
//
// Thread: GUI, with the viewport's context current.

#include "widgets/GlSupport.h"

#include <glm/vec3.hpp>

#include <QOpenGLShaderProgram>
#include <QString>

#include <memory>

namespace wisp {

class BackgroundRenderer {
public:
    BackgroundRenderer() = default;
    ~BackgroundRenderer();
    BackgroundRenderer(const BackgroundRenderer&) = delete;
    BackgroundRenderer& operator=(const BackgroundRenderer&) = delete;

    bool initialize(GlFunctions* gl);
    void release();
    void draw(const glm::vec3& topSrgb, const glm::vec3& bottomSrgb);
    QString error() const { return m_error; }

private:
    GlFunctions* m_gl = nullptr;
    std::unique_ptr<QOpenGLShaderProgram> m_program;
    GLuint m_vao = 0; // empty: core profile draws nothing without one
    QString m_error;
};

} // namespace wisp
