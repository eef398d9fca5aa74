#pragma once
// The hair's shadows from the key light: a deep opacity map (Yuksel & Keyser, "Deep Opacity Maps",
// Eurographics 2008). Two passes from the light, both small (kPixels square) and both drawing each
// strand as a coarse line strip (its points, no subdivision):
//   1. depth: per texel the nearest hair or head (r) and the nearest head (g), metres from the light
//      (min blending, no depth buffer);
//   2. opacity: every hair fragment adds its opacity to each of four layers it lies in front of;
//      the layers start at the nearest depth of pass 1 and end kLayerMetres behind it, so they
//      follow the hair's surface instead of slicing the whole volume (Kim & Neumann's opacity shadow
//      maps need many more slices for the same detail).
// Receivers (hair.vert, head.frag) read the opacity in front of them, interpolated between layers,
// and the head's depth (so the head shadows the hair and itself): see shadow.glsl's comments in
// those shaders. The passes run only when the hair, the head or the light moved: orbiting a paused
// scene under a key light fixed to the head reuses them.
//
// Thread: GUI, with the viewport's context current (every member function).

#include "widgets/GlSupport.h"
#include "widgets/RenderView.h"

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <QOpenGLShaderProgram>
#include <QString>

#include <cstdint>
#include <memory>
#include <vector>

namespace wisp {

class HairRenderer;
class HeadRenderer;
class ThreadPool;

class HairShadowMap {
public:
    static constexpr int kPixels = 256; // the map's size; a texel is about 1.5 mm over a head with long hair
    // Where the four layers end, metres behind the nearest hair or head (Yuksel & Keyser use a few
    // centimetres in all; the first is thin, so the outer hair shades the hair right under it).
    static constexpr float kLayerMetres[4] = { 0.004f, 0.012f, 0.03f, 0.08f };

    HairShadowMap() = default;
    ~HairShadowMap();
    HairShadowMap(const HairShadowMap&) = delete;
    HairShadowMap& operator=(const HairShadowMap&) = delete;

    bool initialize(GlFunctions* gl);
    void release();

    // Draws both passes for a light shining along -lightDirectionWorld (unit, toward the light)
    // onto everything inside the sphere (centre, radius, metres). Leaves the GL viewport and
    // framebuffer binding to the caller to restore. `strandOpacity`: what one strand crossing a
    // texel takes of the light, 0..1. The head and the body are drawn placed by `headToWorld` (the
    // frame's, as the main pass draws them); the hair is in world space already.
    void render(HairRenderer& hair, HeadRenderer& head, HeadRenderer& body, const glm::mat4& headToWorld,
        const glm::vec3& lightDirectionWorld, const glm::vec3& centre, float radiusMetres, float strandOpacity);
    // What receivers need (RenderView::shadow): the map as last rendered.
    ShadowLookup lookup() const;
    bool valid() const { return m_valid; }
    void invalidate() { m_valid = false; }
    std::uint64_t passCount() const { return m_passes; } // render() calls that drew, so far
    // The hair's two passes drawn on the CPU (HairShadowRaster.h) over the head's pass read back
    // from GL, on `pool`'s threads (null: the calling thread); for a software OpenGL, where the
    // strands' lines are most of the passes' cost. Off: GL draws them.
    void setSoftwareHair(bool on, ThreadPool* pool)
    {
        m_softwareHair = on;
        m_softwarePool = pool;
    }
    bool softwareHair() const { return m_softwareHair; }
    QString error() const { return m_error; }

private:
    // The hair's passes and the blurred levels, after the head's pass (the depth framebuffer bound).
    void drawHairOnGl(HairRenderer& hair, float strandOpacity);
    bool drawHairOnCpu(HairRenderer& hair, float strandOpacity);

    GlFunctions* m_gl = nullptr;
    bool m_softwareHair = false;
    ThreadPool* m_softwarePool = nullptr;
    std::vector<glm::vec2> m_cpuDepth; // the software passes' maps, read back and handed back
    std::vector<glm::vec4> m_cpuOpacity;
    std::unique_ptr<QOpenGLShaderProgram> m_hairProgram; // shadow_hair.*: both passes
    std::unique_ptr<QOpenGLShaderProgram> m_headProgram; // shadow_head.*: pass 1
    GLuint m_depthTexture = 0; // RG32F
    GLuint m_opacityTexture = 0; // RGBA16F, mipmapped (the blurred levels are the ambient's density)
    GLuint m_depthFramebuffer = 0;
    GLuint m_opacityFramebuffer = 0;
    glm::mat4 m_worldToShadow{ 1.0f };
    glm::mat4 m_lightViewProjection{ 1.0f };
    bool m_valid = false;
    std::uint64_t m_passes = 0;
    QString m_error;
};

// Sets a receiver's shadow_lookup.glsl uniforms and binds the maps to texture units 2 and 3 (the
// program must be bound); unbindShadowLookup() unbinds them after the draw.
void bindShadowLookup(GlFunctions* gl, QOpenGLShaderProgram& program, const ShadowLookup& shadow);
void unbindShadowLookup(GlFunctions* gl);

} // namespace wisp
