#pragma once
// Draws the head: a smooth-shaded, depth-tested mesh in a skin tone, optionally tinted by the
// painted growth weights (one per vertex) so the artist sees where hair grows.
//
// setMesh() only prepares vertex data on the CPU (smooth normals included); the upload happens on
// the next draw, with the context current, so the head can be set before the widget is shown.
// The weights live in a buffer of their own: a brush stroke changes them many times a second, and
// then only they are sent again (glBufferSubData), never the positions and normals.
// The hair's shadow and ambient at each vertex are looked up once per shadow map (and placement of
// the head), captured by transform feedback into a buffer the drawing reads (head_light.vert): an
// orbit of a paused scene, whose key light is fixed to the head, reads no shadow texels at all.
//
// Thread: GUI. initialize(), release() and draw() need the viewport's context current.

#include "sim/geometry/TriangleMesh.h"
#include "widgets/GlSupport.h"
#include "widgets/RenderView.h"

#include <QOpenGLShaderProgram>
#include <QString>

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace wisp {

class HeadRenderer {
public:
    HeadRenderer() = default;
    ~HeadRenderer();
    HeadRenderer(const HeadRenderer&) = delete;
    HeadRenderer& operator=(const HeadRenderer&) = delete;

    bool initialize(GlFunctions* gl);
    void release();

    // An unusable mesh (see validateMesh) draws nothing.
    void setMesh(const TriangleMesh& mesh);
    // One weight per vertex, 0..1 (others are clamped; non-finite ones read as 0). Kept whatever
    // their count, but shown only while it equals the mesh's vertex count, so the head and its
    // weights may arrive in either order.
    void setGrowthWeights(std::vector<float> weights);
    // Per vertex: sRGB root colour of the hair growing there and its weight (scalpCoverage in
    // sim/groom/GrowthRegion.h); the skin is tinted toward it (the scalp under the hair). Shown while
    // its count equals the mesh's vertices.
    void setScalpCoverage(std::vector<glm::vec4> coverage);
    bool hasGrowthOverlay() const { return !m_weights.empty() && m_weights.size() == m_vertices.size(); }
    // `showGrowthOverlay`: tint by the weights, if there are usable ones; else plain skin.
    void draw(const RenderView& view, bool showGrowthOverlay = false);

    // The mesh's triangles with another program, already bound, whose attribute 0 is the position
    // (the shadow map's depth pass).
    void drawWith(QOpenGLShaderProgram& program);

    // The colour it is shaded in, sRGB 0..1 (the skin tone unless set).
    void setColour(const glm::vec3& srgb) { m_colourSrgb = srgb; }

    QString error() const { return m_error; }
    // How many times the light per vertex was looked up so far (tests: once per shadow map).
    std::uint64_t lightUpdates() const { return m_lightUpdates; }
    static constexpr float kSkinSrgb[3] = { 0.87f, 0.68f, 0.58f };

private:
    struct Vertex {
        glm::vec3 position; // metres
        glm::vec3 normal; // unit, area-weighted vertex normal
    };
    void uploadPending();
    void uploadWeights();
    void uploadCoverage();
    // m_lightBuffer for this shadow map and placement, unless it already holds them.
    void updateLight(const ShadowLookup& shadow, const glm::mat4& modelToWorld);

    GlFunctions* m_gl = nullptr;
    std::unique_ptr<QOpenGLShaderProgram> m_program;
    std::unique_ptr<QOpenGLShaderProgram> m_lightProgram; // head_light.vert (null: the head unshadowed)
    GLuint m_vao = 0;
    GLuint m_vertexBuffer = 0;
    GLuint m_weightBuffer = 0; // one float per vertex, sized with the mesh
    GLuint m_coverageBuffer = 0; // one vec4 per vertex (linear RGB, weight), sized with the mesh
    GLuint m_indexBuffer = 0;
    GLuint m_lightBuffer = 0; // vec2 per vertex: key light, hair ambient (head_light.vert)
    // Positions and normals only, for the lookup's pass: m_vao also reads m_lightBuffer, which that
    // pass writes (a buffer written by transform feedback must not be bound as an attribute too).
    GLuint m_lightVao = 0;
    GLsizei m_indexCount = 0;
    // What m_lightBuffer was looked up for (valid: it holds that, for the mesh as uploaded).
    struct LightKey {
        ShadowLookup shadow;
        glm::mat4 modelToWorld{ 1.0f };
    };
    std::optional<LightKey> m_lightKey;
    std::uint64_t m_lightUpdates = 0;
    // Kept after uploading: a new context (the widget moved to another window) needs them again.
    std::vector<Vertex> m_vertices;
    std::vector<glm::uvec3> m_triangles;
    std::vector<float> m_weights;
    std::vector<glm::vec4> m_coverage; // as given: sRGB, weight
    glm::vec3 m_colourSrgb{ kSkinSrgb[0], kSkinSrgb[1], kSkinSrgb[2] };
    bool m_dirty = false;
    bool m_weightsDirty = false;
    bool m_coverageDirty = false;
    QString m_error;
};

} // namespace wisp
