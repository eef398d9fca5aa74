#pragma once
// Draws a frame's strands as smooth, shaded, tapered hair (see resources/shaders/hair.*).
//
// Per frame the CPU only copies the points into a buffer texture (one pass, which also flags
// strands with non-finite points so the shader drops them); the Catmull-Rom subdivision, the
// Kajiya-Kay shading and the ribbon expansion run in the vertex shader, over a static layout
// (HairStripLayout) rebuilt only when the strands' layout changes. One draw call for all strands.
//
// Colours: the style's root and tip colours, or per strand a look (a region's root and tip colours)
// when the frame assigns one. The look's index rides in the w of each streamed point, which is
// written anyway (no extra per-frame data); the looks' colours sit in a small buffer texture,
// sent again only when they change.
//
// Strands at most a pixel wide on screen are drawn as line strips, wider ones (close-ups) as
// camera-facing ribbons; both carry the strand's true width as coverage in alpha, so the switch
// does not show. draw() can draw an even sample of the strands (level of detail, see HairDetail);
// lines at one sample a segment leave out the points of straight runs (HairLineDecimation).
//
// Thread: GUI, with the viewport's GL context current (every member function).

#include "sim/geometry/HairCurves.h"
#include "sim/geometry/TriangleMesh.h"
#include "sim/solver/Frame.h"
#include "widgets/GlSupport.h"
#include "widgets/HairLineDecimation.h"
#include "widgets/HairShading.h"
#include "widgets/HairSoftwareRaster.h"
#include "widgets/HairStripLayout.h"
#include "widgets/RenderView.h"

#include <glm/vec3.hpp>

#include <QOpenGLShaderProgram>
#include <QString>

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <vector>

namespace wisp {

struct HairStyle {
    glm::vec3 rootColour{ 0.14f, 0.085f, 0.05f }; // sRGB 0..1
    glm::vec3 tipColour{ 0.50f, 0.33f, 0.19f }; // sRGB 0..1
    // One hair's thickness at the root (Param::HairThickness's default; a look's own wins), and
    // at the tip as a fraction of it (io/HairFiles.h exports 80 and 20 µm).
    float hairThicknessMetres = 80e-6f;
    float tipThicknessRatio = 0.25f;
    // A drawn strand stands for a lock of hairs (~20 that overlap): it is drawn this many hair
    // thicknesses wide (0.6 mm at the default thickness), so the hair covers the scalp.
    float lockWidthScale = 7.5f;
    float rootWidthMetres() const { return hairThicknessMetres * lockWidthScale; } // the style's drawn width
    float minWidthPixels = 1.0f; // narrower strands are drawn this wide, fainter
    float tipFade = 0.6f; // how far the tip fades out, 0..1
    // Curves get as few Catmull-Rom samples per segment (1, 2 or 4) as keep the chords within this
    // many pixels of the curve (HairSampling.h); more would cost vertices and show nothing.
    float maxDeviationPixels = 0.5f;
};

class HairRenderer {
public:
    HairRenderer() = default;
    ~HairRenderer(); // GL objects must already be released (release() with the context current)
    HairRenderer(const HairRenderer&) = delete;
    HairRenderer& operator=(const HairRenderer&) = delete;

    // False (and why, in error()) when the shaders do not build; draw() then does nothing.
    bool initialize(GlFunctions* gl);
    void release();

    // The looks that upload()'s lookOfStrand indexes (sRGB colours; at most 65536). Cheap when
    // they have not changed. Call before upload(): a strand names a look only if it exists then.
    void setLooks(std::span<const StrandLook> looks);
    // Streams the strands in; `strands` need only live for this call. `lookOfStrand`: one look
    // index per strand, or empty (or of another count) for the style's colours everywhere; a
    // strand whose index has no look also takes the style's colours.
    void upload(const HairCurves& strands, std::span<const std::uint16_t> lookOfStrand = {},
        std::span<const float> wetness = {});
    void clear();
    // Draws `fraction` (0..1) of the strands, an even sample, each made wider to make up for the
    // rest; `coarse` draws one sample per segment (the points themselves) whatever the zoom.
    void draw(const RenderView& view, const HairStyle& style, float fraction = 1.0f, bool coarse = false);
    // The software path (widgets/HairSoftwareRaster.h, HairShading.h; the viewport takes it on a
    // software OpenGL while the view moves): draw()'s strands, with draw()'s choices (share, lines or
    // ribbons, samples a segment, straight runs thinned), for a target view.viewportPixels big.
    // prepareSoftware() captures what their centre lines' samples are whatever the view, by
    // transform feedback, only when that changed (the frame, the looks, the shadow map, the level of
    // detail); drawSoftware() shades them for the view and draws them on the CPU: the target's pixels
    // inside `region`, premultiplied RGBA8, rows bottom up, `depth` the backdrop's over the region
    // (empty: none); the span lives until the next call. prepareSoftware() is false (and
    // drawSoftware() empty) where the capture program did not build or the frame is empty.
    bool prepareSoftware(const RenderView& view, const HairStyle& style, float fraction = 1.0f, bool coarse = false);
    std::span<const std::uint8_t> drawSoftware(const PixelRect& region, std::span<const float> depth, ThreadPool* pool);
    std::uint64_t worldCaptures() const { return m_worldCaptures; } // prepareSoftware()'s GL passes
    // The centre lines' samples for a view as GL's vertex shader shades them (hair_samples.vert) or
    // as the CPU does (HairShading.h): the two paths must agree (HairLowResTest checks).
    std::vector<HairRasterSample> shadedSamples(
        const RenderView& view, const HairStyle& style, float fraction, bool coarse, bool onCpu);

    // Whether draw() writes the strands' depth (it always tests it). Into a target whose pixels are
    // larger than the frame's (HairLowResTarget), not: a partly covering strand in front would hide
    // the strands beside it that share its pixel there but not in the frame.
    void setDepthWrites(bool on) { m_depthWrites = on; }

    // Every strand as a line strip through its points (no subdivision), with another program,
    // already bound, that reads the points as hair.vert does (unit 0) from attribute 0 (the shadow
    // map's passes).
    void drawPoints(QOpenGLShaderProgram& program);
    // The last upload's points as the shaders read them (xyz world metres; w: the strand's tag, below
    // 0.5 for a strand with a non-finite point, not drawn), and its strands' offsets into them.
    std::span<const glm::vec4> points() const
    {
        return m_vertexCount > 0 ? std::span<const glm::vec4>(m_points) : std::span<const glm::vec4>();
    }
    std::span<const std::uint32_t> strandOffsets() const { return m_layout.offsets; }
    // The box around the last upload's finite points (empty before any).
    const Aabb& bounds() const { return m_bounds; }
    // bounds() widened by half the widest strand that draw(view, style, fraction) would draw,
    // metres: the space its ribbons can reach (lines and the antialiasing skirt add pixels).
    Aabb drawnBounds(const HairStyle& style, float fraction) const;

    QString error() const { return m_error; }
    std::size_t strandCount() const { return m_vertexCount > 0 ? m_layout.drawnStrands : 0; } // drawable
    std::size_t skippedStrands() const { return m_skippedStrands; } // had non-finite points
    std::size_t lastDrawnStrands() const { return m_lastDrawnStrands; }
    bool lastDrewLines() const { return m_lastDrewLines; }
    bool lastDrewTwoPasses() const { return m_lastDrewTwoPasses; } // ribbons from captured samples
    // Line segments the last draw() drew (0 for ribbons): fewer than the points' segments where
    // straight runs were drawn with fewer (HairLineDecimation.h).
    std::size_t lastDrawnLineSegments() const { return m_lastDrawnLineSegments; }
    // Leaving out points on straight runs of lines (on by default; WISP_NO_LINE_DECIMATION=1 in the
    // environment turns it off to compare).
    void setLineDecimation(bool on) { m_lineDecimation = on; }
    int lastSamplesPerSegment() const { return m_lastSamplesPerSegment; }

private:
    // What draw() and captureSamples() draw for a view, style and share.
    struct DrawPlan {
        std::size_t drawn = 0; // the first `drawn` strands in drawing order
        float widthScale = 1.0f;
        bool lines = true;
        std::size_t stepIndex = 0; // in HairStripLayout::kSampleSteps
        const HairStripLayout::IndexList* list = nullptr; // the strips draw() draws
        const HairStripLayout::IndexList* centreLine = nullptr; // their centre lines (left vertices)
        GLuint elementBuffer = 0; // holding both lists
        std::size_t byteOffset = 0; // of `list` in elementBuffer
        std::size_t centreLineByteOffset = 0;
        GLsizei indexCount = 0; // of `list`, for `drawn` strands
    };
    DrawPlan planDraw(const RenderView& view, const HairStyle& style, float fraction, bool coarse);
    // Transform feedback of `program` (one of the sample programs) over the plan's centre lines,
    // one sample each, into `buffer` (grown to `capacity` samples as needed).
    bool captureWithProgram(QOpenGLShaderProgram& program, const DrawPlan& plan, const RenderView& view,
        const HairStyle& style, GLuint buffer, std::size_t bytesPerSample, std::size_t& capacity);
    HairShadingView shadingView(const RenderView& view, const HairStyle& style, const DrawPlan& plan) const;
    // The strands' points (unit 0) and looks (unit 1), as hair_strand.glsl reads them; and off again.
    void bindStrandTextures();
    void unbindStrandTextures();
    // Calls `use` with the captured world samples (mapped); false if none or the map failed.
    bool withWorldSamples(const std::function<void(std::span<const HairWorldSample>)>& use);
    // What the world capture was made from.
    struct WorldKey {
        std::uint64_t revision = 0; // m_worldRevision: points, looks, layout, thinned lines
        const HairStripLayout::IndexList* list = nullptr;
        std::size_t drawn = 0;
        ShadowLookup shadow;
        glm::vec3 rootColour{ 0.0f };
        glm::vec3 tipColour{ 0.0f };
        float thicknessMetres = 0.0f;
        bool operator==(const WorldKey& o) const
        {
            return revision == o.revision && list == o.list && drawn == o.drawn && shadow.sameAs(o.shadow)
                && rootColour == o.rootColour && tipColour == o.tipColour && thicknessMetres == o.thicknessMetres;
        }
    };
    // How many strands draw() draws for `fraction`, and how much wider each is for those it leaves out.
    struct DrawnShare {
        std::size_t strands = 0;
        float widthScale = 1.0f;
    };
    DrawnShare drawnShare(float fraction) const;

    void rebuildLayout(std::span<const std::uint32_t> offsets);
    void rebuildDecimatedLines(float toleranceMetres);
    void uploadLooks();
    // The uniforms hair_strand.glsl reads, on a bound program.
    void setStrandUniforms(QOpenGLShaderProgram& program, const RenderView& view, const HairStyle& style,
        float widthScale, bool lines) const;
    // Ribbons in two passes: the first `samples` samples evaluated once each into m_sampleBuffer,
    // then both edges read from it. False (nothing drawn) when the passes are unavailable.
    bool drawRibbonsFromSamples(std::size_t samples, GLsizei indexCount, std::size_t byteOffset);

    GlFunctions* m_gl = nullptr;
    std::unique_ptr<QOpenGLShaderProgram> m_program;
    // Two-pass ribbons (hair_samples.vert captured by transform feedback, then hair_ribbon.vert):
    // a ribbon's two edges share one evaluation of the spline and the shading, half the vertex work
    // of the one-pass hair.vert, which a software rasteriser does on a single thread.
    std::unique_ptr<QOpenGLShaderProgram> m_sampleProgram;
    std::unique_ptr<QOpenGLShaderProgram> m_ribbonProgram;
    GLuint m_sampleVao = 0; // the layout's left-edge vertices only (stride two vertices)
    GLuint m_sampleBuffer = 0; // three vec4 per sample, read through m_sampleTexture
    GLuint m_sampleTexture = 0;
    std::size_t m_sampleCapacity = 0; // samples m_sampleBuffer can hold
    GLuint m_captureBuffer = 0; // shadedSamples() from GL: HairRasterSample per sample
    std::size_t m_captureCapacity = 0; // samples it can hold
    std::unique_ptr<QOpenGLShaderProgram> m_worldProgram; // hair_sample_world.vert
    GLuint m_worldBuffer = 0; // HairWorldSample per sample of the software path
    std::size_t m_worldCapacity = 0;
    std::uint64_t m_worldRevision = 0;
    std::optional<WorldKey> m_worldKey; // what m_worldBuffer holds; none: nothing
    std::uint64_t m_worldCaptures = 0;
    std::size_t m_softwareSamples = 0;
    std::vector<std::uint32_t> m_softwareStrandEnds;
    HairShadingView m_softwareView;
    std::vector<HairRasterSample> m_shaded;
    HairSoftwareRaster m_raster;
    GLuint m_vao = 0;
    GLuint m_layoutBuffer = 0; // HairStripLayout::vertices
    GLuint m_indexBuffer = 0; // every index list of m_layout, one after another (element buffer of m_vao)
    // Lines with the straight runs' points left out (HairLineDecimation.h), for a tolerance: rebuilt
    // when the frame changes or the zoom asks for a finer one (or a much coarser one).
    GLuint m_decimatedIndexBuffer = 0;
    std::vector<float> m_chordDeviations; // per point of the last upload, metres
    HairStripLayout::IndexList m_decimatedLines;
    float m_decimatedToleranceMetres = -1.0f; // what m_decimatedLines was built for; < 0: none
    bool m_lineDecimation = true;
    std::size_t m_lastDrawnLineSegments = 0;
    GLuint m_pointBuffer = 0; // vec4 per point, read through m_pointTexture
    std::vector<glm::vec4> m_points; // what m_pointBuffer holds
    GLuint m_pointTexture = 0;
    GLuint m_lookBuffer = 0; // two linear-RGBA texels per look: root, tip
    GLuint m_lookTexture = 0;
    std::vector<StrandLook> m_looks; // as last given (sRGB); m_lookBuffer holds them
    float m_thickestLookMetres = 0.0f; // the largest rootThicknessMetres of m_looks
    std::size_t m_pointCapacity = 0; // points m_pointBuffer can hold
    GLint m_maxTexels = 0; // GL_MAX_TEXTURE_BUFFER_SIZE: frames with more points are not drawn
    HairStripLayout m_layout;
    // Byte offset of each index list in m_indexBuffer: [primitive][step].
    std::array<std::array<std::size_t, 3>, 2> m_indexOffsets{};
    Aabb m_bounds;
    float m_segmentMetres = 0.0f; // typical segment length of the last frame
    float m_longestSegmentMetres = 0.0f; // of the last upload's finite strands
    float m_turnRadians = 0.0f; // typical turn at a joint of the last frame (typicalTurnRadians)
    GLsizei m_vertexCount = 0; // 0: nothing to draw
    std::size_t m_skippedStrands = 0;
    std::size_t m_lastDrawnStrands = 0;
    bool m_lastDrewLines = false;
    bool m_depthWrites = true;
    bool m_lastDrewTwoPasses = false;
    int m_lastSamplesPerSegment = 0;
    QString m_error;
};

} // namespace wisp
