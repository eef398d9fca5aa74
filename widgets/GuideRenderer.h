#pragma once
// Draws the scene guides built by GuideGeometry: the ground grid (thin blended lines, depth-tested
// so the head hides it), the wind arrow (a shaded solid) and the paint brush's rings (flat bands on
// the scalp, drawn over everything else).
//
// set*() keep the geometry on the CPU and mark it for upload on the next draw.
// Thread: GUI; initialize(), release() and draw*() need the viewport's context current.

#include "widgets/GlSupport.h"
#include "widgets/GuideGeometry.h"
#include "widgets/RenderView.h"

#include <QOpenGLShaderProgram>
#include <QString>

#include <memory>
#include <vector>

namespace wisp {

class GuideRenderer {
public:
    GuideRenderer() = default;
    ~GuideRenderer();
    GuideRenderer(const GuideRenderer&) = delete;
    GuideRenderer& operator=(const GuideRenderer&) = delete;

    bool initialize(GlFunctions* gl);
    void release();

    void setGrid(GroundGrid grid);
    void setWindArrow(WindArrow arrow);
    const WindArrow& windArrow() const { return m_arrow; }
    // Triangles from buildBrushRings; empty: no brush.
    void setBrushRings(std::vector<GuideVertex> triangles);

    void drawWindArrow(const RenderView& view);
    void drawGrid(const RenderView& view);
    // Depth-tested against the head and hair, pulled slightly toward the camera; the parts they
    // hide show faintly through them, so the brush is never lost under the hair it paints beneath.
    void drawBrushRings(const RenderView& view);

    QString error() const { return m_error; }

private:
    struct Mesh {
        GLuint vao = 0;
        GLuint buffer = 0;
        GLsizei count = 0;
        bool dirty = false;
    };
    void createMesh(Mesh& mesh);
    void upload(Mesh& mesh, const std::vector<GuideVertex>& vertices);
    void bindProgram(const RenderView& view, float lit, float fadeRadius);
    void drawBrushPass(GLsizei count, float alphaScale);

    GlFunctions* m_gl = nullptr;
    std::unique_ptr<QOpenGLShaderProgram> m_program;
    Mesh m_gridMesh;
    Mesh m_arrowMesh;
    Mesh m_brushMesh;
    GroundGrid m_grid;
    WindArrow m_arrow;
    std::vector<GuideVertex> m_brushRings;
    QString m_error;
};

} // namespace wisp
