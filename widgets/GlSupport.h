#pragma once
// What every GL piece of the viewport shares: one function table (OpenGL 3.3 core, nothing newer),
// shader programs from the resources, and error checks that cost nothing in release builds.
//
// Thread: GUI, with the viewport's context current.

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <QOpenGLFunctions_3_3_Core>
#include <QString>

#include <memory>
#include <vector>

class QOpenGLShaderProgram;

namespace wisp {

using GlFunctions = QOpenGLFunctions_3_3_Core;

// Compiles and links ":/shaders/<name>.vert" and ".frag". Null (and the log in *error) on failure.
std::unique_ptr<QOpenGLShaderProgram> loadShaderProgram(const QString& name, QString* error);
// The same with :/shaders/VERTEX.vert and :/shaders/FRAGMENT.frag (passes that share a vertex shader).
std::unique_ptr<QOpenGLShaderProgram> loadShaderProgram(
    const QString& vertexName, const QString& fragmentName, QString* error);
// A vertex shader alone (":/shaders/<vertexName>.vert") whose outputs `varyings` are captured,
// interleaved, by transform feedback (drawn with GL_RASTERIZER_DISCARD).
std::unique_ptr<QOpenGLShaderProgram> loadTransformFeedbackProgram(
    GlFunctions* gl, const QString& vertexName, const std::vector<const char*>& varyings, QString* error);

// Uniforms from GLM values (column-major, as GL wants them). A name the program does not use (the
// compiler dropped it) is ignored, as GL ignores location -1.
void setUniform(QOpenGLShaderProgram& program, const char* name, const glm::mat4& value);
void setUniform(QOpenGLShaderProgram& program, const char* name, const glm::vec4& value);
void setUniform(QOpenGLShaderProgram& program, const char* name, const glm::vec3& value);
void setUniform(QOpenGLShaderProgram& program, const char* name, const glm::vec2& value);
void setUniform(QOpenGLShaderProgram& program, const char* name, float value);
void setUniform(QOpenGLShaderProgram& program, const char* name, int value);

// sRGB colour components (0..1) to linear light, where shaders do their lighting.
glm::vec3 linearFromSrgb(const glm::vec3& srgb);

// Drains glGetError and logs each error with `where`. Debug builds only: glGetError stalls a
// pipelined driver, which would cost the release build's frame rate for nothing.
#ifndef NDEBUG
void checkGlErrors(GlFunctions* gl, const char* where);
#else
inline void checkGlErrors(GlFunctions*, const char*)
{
}
#endif

} // namespace wisp
