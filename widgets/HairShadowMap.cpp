#include "widgets/HairShadowMap.h"

#include "widgets/HairRenderer.h"
#include "widgets/HairShadowRaster.h"
#include "widgets/HeadRenderer.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace wisp {
namespace {

// Farther than anything: what a texel with nothing in it reads as its depth.
constexpr float kFarMetres = 1e6f;

GLuint makeTexture(GlFunctions* gl, GLint internalFormat, GLenum format, bool mipmapped)
{
    GLuint texture = 0;
    gl->glGenTextures(1, &texture);
    gl->glBindTexture(GL_TEXTURE_2D, texture);
    gl->glTexImage2D(
        GL_TEXTURE_2D, 0, internalFormat, HairShadowMap::kPixels, HairShadowMap::kPixels, 0, format, GL_FLOAT, nullptr);
    gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, mipmapped ? GL_LINEAR_MIPMAP_LINEAR : GL_NEAREST);
    gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, mipmapped ? GL_LINEAR : GL_NEAREST);
    gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    if (mipmapped)
        gl->glGenerateMipmap(GL_TEXTURE_2D);
    gl->glBindTexture(GL_TEXTURE_2D, 0);
    return texture;
}

GLuint makeFramebuffer(GlFunctions* gl, GLuint texture)
{
    GLuint framebuffer = 0;
    gl->glGenFramebuffers(1, &framebuffer);
    gl->glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    gl->glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture, 0);
    const bool complete = gl->glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    gl->glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (!complete) {
        gl->glDeleteFramebuffers(1, &framebuffer);
        return 0;
    }
    return framebuffer;
}

} // namespace

HairShadowMap::~HairShadowMap() = default;

bool HairShadowMap::initialize(GlFunctions* gl)
{
    m_gl = gl;
    m_valid = false;
    m_hairProgram = loadShaderProgram(QStringLiteral("shadow_hair"), &m_error);
    if (!m_hairProgram)
        return false;
    m_headProgram = loadShaderProgram(QStringLiteral("shadow_head"), &m_error);
    if (!m_headProgram)
        return false;
    m_depthTexture = makeTexture(gl, GL_RG32F, GL_RG, false);
    m_opacityTexture = makeTexture(gl, GL_RGBA16F, GL_RGBA, true);
    m_depthFramebuffer = makeFramebuffer(gl, m_depthTexture);
    m_opacityFramebuffer = makeFramebuffer(gl, m_opacityTexture);
    if (!m_depthFramebuffer || !m_opacityFramebuffer) {
        m_error = QStringLiteral("HairShadowMap: float framebuffers are not supported; the hair casts no shadows");
        release();
        return false;
    }
    m_hairProgram->bind();
    m_hairProgram->setUniformValue("u_points", 0);
    m_hairProgram->setUniformValue("u_depth", 2);
    m_hairProgram->release();
    checkGlErrors(gl, "HairShadowMap::initialize");
    return true;
}

void HairShadowMap::release()
{
    if (!m_gl)
        return;
    m_gl->glDeleteFramebuffers(1, &m_opacityFramebuffer);
    m_gl->glDeleteFramebuffers(1, &m_depthFramebuffer);
    m_gl->glDeleteTextures(1, &m_opacityTexture);
    m_gl->glDeleteTextures(1, &m_depthTexture);
    m_opacityFramebuffer = m_depthFramebuffer = m_opacityTexture = m_depthTexture = 0;
    m_hairProgram.reset();
    m_headProgram.reset();
    m_gl = nullptr;
    m_valid = false;
}

void HairShadowMap::render(HairRenderer& hair, HeadRenderer& head, HeadRenderer& body, const glm::mat4& headToWorld,
    const glm::vec3& lightDirectionWorld, const glm::vec3& centre, float radiusMetres, float strandOpacity)
{
    if (!m_gl || !m_hairProgram || !m_headProgram || !(radiusMetres > 0.0f) || !std::isfinite(radiusMetres))
        return;
    GlFunctions* gl = m_gl;
    const float r = radiusMetres;
    // An orthographic view down the light: the key light is far away compared with a head.
    const glm::vec3 towardLight = glm::normalize(lightDirectionWorld);
    const glm::vec3 up = std::abs(towardLight.y) > 0.95f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
    const glm::vec3 eye = centre + towardLight * (2.0f * r);
    const glm::mat4 lightView = glm::lookAt(eye, centre, up);
    m_lightViewProjection = glm::ortho(-r, r, -r, r, 0.0f, 4.0f * r) * lightView;
    // (u, v, distance from the light): x, y from -r..r to 0..1, z from -distance to distance.
    glm::mat4 toMap(1.0f);
    toMap[0][0] = 0.5f / r;
    toMap[1][1] = 0.5f / r;
    toMap[2][2] = -1.0f;
    toMap[3][0] = 0.5f;
    toMap[3][1] = 0.5f;
    m_worldToShadow = toMap * lightView;

    gl->glViewport(0, 0, kPixels, kPixels);
    gl->glDisable(GL_DEPTH_TEST);
    gl->glDepthMask(GL_FALSE);
    gl->glDisable(GL_CULL_FACE);
    gl->glDisable(GL_SCISSOR_TEST);
    gl->glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl->glEnable(GL_BLEND);

    // Pass 1: nearest depths.
    gl->glBindFramebuffer(GL_FRAMEBUFFER, m_depthFramebuffer);
    gl->glClearColor(kFarMetres, kFarMetres, 0.0f, 0.0f);
    gl->glClear(GL_COLOR_BUFFER_BIT);
    gl->glBlendEquation(GL_MIN);
    gl->glBlendFunc(GL_ONE, GL_ONE);
    m_headProgram->bind();
    setUniform(*m_headProgram, "u_lightViewProjection", m_lightViewProjection);
    setUniform(*m_headProgram, "u_worldToShadow", m_worldToShadow);
    setUniform(*m_headProgram, "u_modelToWorld", headToWorld);
    head.drawWith(*m_headProgram);
    body.drawWith(*m_headProgram);
    m_headProgram->release();
    if (!m_softwareHair || !drawHairOnCpu(hair, strandOpacity))
        drawHairOnGl(hair, strandOpacity);

    gl->glDisable(GL_BLEND);
    gl->glBlendEquation(GL_FUNC_ADD);
    gl->glDepthMask(GL_TRUE);
    gl->glBindFramebuffer(GL_FRAMEBUFFER, 0);
    m_valid = true;
    ++m_passes;
    checkGlErrors(gl, "HairShadowMap::render");
}

void HairShadowMap::drawHairOnGl(HairRenderer& hair, float strandOpacity)
{
    GlFunctions* gl = m_gl;
    m_hairProgram->bind();
    setUniform(*m_hairProgram, "u_lightViewProjection", m_lightViewProjection);
    setUniform(*m_hairProgram, "u_worldToShadow", m_worldToShadow);
    setUniform(*m_hairProgram, "u_pass", 0);
    setUniform(*m_hairProgram, "u_strandOpacity", strandOpacity);
    setUniform(
        *m_hairProgram, "u_layerMetres", glm::vec4(kLayerMetres[0], kLayerMetres[1], kLayerMetres[2], kLayerMetres[3]));
    hair.drawPoints(*m_hairProgram);

    // Pass 2: opacity per layer, reading pass 1.
    gl->glBindFramebuffer(GL_FRAMEBUFFER, m_opacityFramebuffer);
    gl->glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    gl->glClear(GL_COLOR_BUFFER_BIT);
    gl->glBlendEquation(GL_FUNC_ADD);
    gl->glBlendFunc(GL_ONE, GL_ONE);
    gl->glActiveTexture(GL_TEXTURE2);
    gl->glBindTexture(GL_TEXTURE_2D, m_depthTexture);
    gl->glActiveTexture(GL_TEXTURE0);
    setUniform(*m_hairProgram, "u_pass", 1);
    hair.drawPoints(*m_hairProgram);
    m_hairProgram->release();
    gl->glActiveTexture(GL_TEXTURE2);
    gl->glBindTexture(GL_TEXTURE_2D, 0);
    gl->glActiveTexture(GL_TEXTURE0);

    // The blurred levels stand for the hair's density around a point (the ambient term).
    gl->glBindTexture(GL_TEXTURE_2D, m_opacityTexture);
    gl->glGenerateMipmap(GL_TEXTURE_2D);
    gl->glBindTexture(GL_TEXTURE_2D, 0);
}

bool HairShadowMap::drawHairOnCpu(HairRenderer& hair, float strandOpacity)
{
    GlFunctions* gl = m_gl;
    constexpr std::size_t kTexels = static_cast<std::size_t>(kPixels) * kPixels;
    m_cpuDepth.resize(kTexels);
    m_cpuOpacity.resize(kTexels);
    // The head's pass, as drawn above (the depth framebuffer is bound).
    gl->glPixelStorei(GL_PACK_ALIGNMENT, 4);
    gl->glPixelStorei(GL_PACK_ROW_LENGTH, 0);
    gl->glReadPixels(0, 0, kPixels, kPixels, GL_RG, GL_FLOAT, m_cpuDepth.data());
    ShadowRasterInput input;
    input.points = hair.points();
    input.strandOffsets = hair.strandOffsets();
    input.lightViewProjection = m_lightViewProjection;
    input.worldToShadow = m_worldToShadow;
    input.pixels = kPixels;
    input.layerMetres = glm::vec4(kLayerMetres[0], kLayerMetres[1], kLayerMetres[2], kLayerMetres[3]);
    input.strandOpacity = strandOpacity;
    drawShadowHair(input, m_cpuDepth, m_cpuOpacity, m_softwarePool);
    gl->glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl->glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    gl->glBindTexture(GL_TEXTURE_2D, m_depthTexture);
    gl->glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, kPixels, kPixels, GL_RG, GL_FLOAT, m_cpuDepth.data());
    gl->glBindTexture(GL_TEXTURE_2D, m_opacityTexture);
    gl->glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, kPixels, kPixels, GL_RGBA, GL_FLOAT, m_cpuOpacity.data());
    // The blurred levels stand for the hair's density around a point (the ambient term).
    gl->glGenerateMipmap(GL_TEXTURE_2D);
    gl->glBindTexture(GL_TEXTURE_2D, 0);
    return true;
}

ShadowLookup HairShadowMap::lookup() const
{
    ShadowLookup out;
    out.enabled = m_valid;
    out.worldToShadow = m_worldToShadow;
    out.depthTexture = m_depthTexture;
    out.opacityTexture = m_opacityTexture;
    out.layerMetres = glm::vec4(kLayerMetres[0], kLayerMetres[1], kLayerMetres[2], kLayerMetres[3]);
    out.revision = m_passes;
    return out;
}

void bindShadowLookup(GlFunctions* gl, QOpenGLShaderProgram& program, const ShadowLookup& shadow)
{
    setUniform(program, "u_shadows", shadow.enabled ? 1.0f : 0.0f);
    setUniform(program, "u_worldToShadow", shadow.worldToShadow);
    setUniform(program, "u_shadowLayers", shadow.layerMetres);
    setUniform(program, "u_shadowDepth", 2);
    setUniform(program, "u_shadowOpacity", 3);
    // Bound even when off: a sampler must refer to a complete texture (0 is none, which is fine
    // for GL as long as nothing is read, and the shader reads nothing then).
    gl->glActiveTexture(GL_TEXTURE2);
    gl->glBindTexture(GL_TEXTURE_2D, shadow.enabled ? shadow.depthTexture : 0);
    gl->glActiveTexture(GL_TEXTURE3);
    gl->glBindTexture(GL_TEXTURE_2D, shadow.enabled ? shadow.opacityTexture : 0);
    gl->glActiveTexture(GL_TEXTURE0);
}

void unbindShadowLookup(GlFunctions* gl)
{
    gl->glActiveTexture(GL_TEXTURE2);
    gl->glBindTexture(GL_TEXTURE_2D, 0);
    gl->glActiveTexture(GL_TEXTURE3);
    gl->glBindTexture(GL_TEXTURE_2D, 0);
    gl->glActiveTexture(GL_TEXTURE0);
}

} // namespace wisp
