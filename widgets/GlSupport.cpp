#include "widgets/GlSupport.h"

#include <QDebug>
#include <QFile>
#include <QMatrix4x4>
#include <QOpenGLShaderProgram>

#include <glm/common.hpp>
#include <glm/exponential.hpp>

namespace wisp {

namespace {

// A shader's text with each line `#include "FILE"` replaced by :/shaders/FILE (GLSL 3.30 has no
// includes; shadow_lookup.glsl is shared by the hair and the head). Empty if a file is missing.
QByteArray shaderSource(const QString& path)
{
    QFile file(path);
    if (!file.open(QIODevice::ReadOnly))
        return {};
    QByteArray out;
    for (const QByteArray& line : file.readAll().split('\n')) {
        const QByteArray trimmed = line.trimmed();
        if (trimmed.startsWith("#include \"") && trimmed.endsWith('"')) {
            const QByteArray included
                = shaderSource(QStringLiteral(":/shaders/") + QString::fromUtf8(trimmed.mid(10, trimmed.size() - 11)));
            if (included.isEmpty())
                return {};
            out += included;
        } else {
            out += line;
        }
        out += '\n';
    }
    return out;
}

} // namespace

std::unique_ptr<QOpenGLShaderProgram> loadShaderProgram(const QString& name, QString* error)
{
    return loadShaderProgram(name, name, error);
}

std::unique_ptr<QOpenGLShaderProgram> loadShaderProgram(
    const QString& vertexName, const QString& fragmentName, QString* error)
{
    auto program = std::make_unique<QOpenGLShaderProgram>();
    const QString name = fragmentName;
    const QByteArray vertex = shaderSource(QStringLiteral(":/shaders/") + vertexName + QStringLiteral(".vert"));
    const QByteArray fragment = shaderSource(QStringLiteral(":/shaders/") + fragmentName + QStringLiteral(".frag"));
    if (vertex.isEmpty() || fragment.isEmpty() || !program->addShaderFromSourceCode(QOpenGLShader::Vertex, vertex)
        || !program->addShaderFromSourceCode(QOpenGLShader::Fragment, fragment) || !program->link()) {
        if (error)
            *error = name + QStringLiteral(": ") + program->log();
        return nullptr;
    }
    return program;
}

std::unique_ptr<QOpenGLShaderProgram> loadTransformFeedbackProgram(
    GlFunctions* gl, const QString& vertexName, const std::vector<const char*>& varyings, QString* error)
{
    auto program = std::make_unique<QOpenGLShaderProgram>();
    const QByteArray vertex = shaderSource(QStringLiteral(":/shaders/") + vertexName + QStringLiteral(".vert"));
    if (vertex.isEmpty() || !program->addShaderFromSourceCode(QOpenGLShader::Vertex, vertex)) {
        if (error)
            *error = vertexName + QStringLiteral(": ") + program->log();
        return nullptr;
    }
    // Before linking: the varyings are part of the link.
    gl->glTransformFeedbackVaryings(
        program->programId(), static_cast<GLsizei>(varyings.size()), varyings.data(), GL_INTERLEAVED_ATTRIBS);
    if (!program->link()) {
        if (error)
            *error = vertexName + QStringLiteral(": ") + program->log();
        return nullptr;
    }
    return program;
}

void setUniform(QOpenGLShaderProgram& program, const char* name, const glm::mat4& value)
{
    // QMatrix4x4's float constructor reads row-major; GLM stores columns.
    program.setUniformValue(name, QMatrix4x4(&value[0][0]).transposed());
}

void setUniform(QOpenGLShaderProgram& program, const char* name, const glm::vec4& value)
{
    program.setUniformValue(name, value.x, value.y, value.z, value.w);
}

void setUniform(QOpenGLShaderProgram& program, const char* name, const glm::vec3& value)
{
    program.setUniformValue(name, value.x, value.y, value.z);
}

void setUniform(QOpenGLShaderProgram& program, const char* name, const glm::vec2& value)
{
    program.setUniformValue(name, value.x, value.y);
}

void setUniform(QOpenGLShaderProgram& program, const char* name, float value)
{
    program.setUniformValue(name, value);
}

void setUniform(QOpenGLShaderProgram& program, const char* name, int value)
{
    program.setUniformValue(name, value);
}

glm::vec3 linearFromSrgb(const glm::vec3& srgb)
{
    return glm::pow(glm::clamp(srgb, 0.0f, 1.0f), glm::vec3(2.2f));
}

#ifndef NDEBUG
void checkGlErrors(GlFunctions* gl, const char* where)
{
    if (!gl)
        return;
    // A bounded loop: a lost context can report errors forever.
    for (int i = 0; i < 16; ++i) {
        const GLenum code = gl->glGetError();
        if (code == GL_NO_ERROR)
            return;
        qWarning("GL error 0x%04x in %s", static_cast<unsigned>(code), where);
    }
}
#endif

} // namespace wisp
