#pragma once
// Draws the head: a smooth-shaded, depth-tested mesh in a skin tone.
//
// setMesh() only prepares vertex data on the CPU (smooth normals included); the upload happens on
// the next draw, with the context current, so the head can be set before the widget is shown.
//
// Thread: GUI. initialize(), release() and draw() need the viewport's context current.

#include "sim/TriangleMesh.h"
#include "widgets/GlSupport.h"
#include "widgets/RenderView.h"

#include <QOpenGLShaderProgram>
#include <QString>

#include <memory>
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
    void draw(const RenderView& view);

    QString error() const { return m_error; }
    static constexpr float kSkinSrgb[3] = { 0.87f, 0.68f, 0.58f };

private:
    struct Vertex {
        glm::vec3 position; // metres
        glm::vec3 normal; // unit, area-weighted vertex normal
    };
    void uploadPending();

    GlFunctions* m_gl = nullptr;
    std::unique_ptr<QOpenGLShaderProgram> m_program;
    GLuint m_vao = 0;
    GLuint m_vertexBuffer = 0;
    GLuint m_indexBuffer = 0;
    GLsizei m_indexCount = 0;
    // Kept after uploading: a new context (the widget moved to another window) needs them again.
    std::vector<Vertex> m_vertices;
    std::vector<glm::uvec3> m_triangles;
    bool m_dirty = false;
    QString m_error;
};

} // namespace wisp
