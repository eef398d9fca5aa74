#pragma once
// What a renderer needs to know about the view it draws into: one value per frame, filled by the
// viewport from its camera, so renderers never read the camera or the widget themselves.

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>

namespace wisp {

// The key light's deep opacity map (HairShadowMap), as receivers read it.
struct ShadowLookup {
    bool enabled = false;
    // World point -> (u, v) in the map (0..1) and z = its distance from the light, metres.
    glm::mat4 worldToShadow{ 1.0f };
    unsigned depthTexture = 0; // r: nearest hair or head, g: nearest head (metres from the light)
    unsigned opacityTexture = 0; // opacity in front of the end of each of the four layers
    glm::vec4 layerMetres{ 0.0f }; // where the layers end, behind the depth in r
    // Counts the map's renders: the same revision (and matrix and textures) reads the same shadows,
    // so a receiver may keep what it looked up (HeadRenderer's light per vertex).
    std::uint64_t revision = 0;

    bool sameAs(const ShadowLookup& o) const
    {
        return enabled == o.enabled && revision == o.revision && worldToShadow == o.worldToShadow
            && depthTexture == o.depthTexture && opacityTexture == o.opacityTexture && layerMetres == o.layerMetres;
    }
};

struct RenderView {
    glm::mat4 view{ 1.0f };
    glm::mat4 projection{ 1.0f };
    glm::mat4 viewProjection{ 1.0f };
    glm::vec2 viewportPixels{ 1.0f }; // framebuffer size in device pixels
    // The key light is fixed to the head (or to the camera, on request: see Viewport); the fill is
    // a head-lamp fixed to the camera. Unit vectors toward the lights, view space.
    glm::vec3 keyLightView{ 0.0f, 0.0f, 1.0f };
    glm::vec3 fillLightView{ 0.0f, 0.0f, 1.0f };
    glm::vec3 headCentreView{ 0.0f }; // the head's centre in view space, metres (hair's volume normals)
    float headRadiusMetres = 0.1f;
    int samples = 0; // MSAA samples of the target framebuffer (0 or 1: none)
    ShadowLookup shadow;
    // The drawn mesh's model space to world (withModel): receivers look their shadows up at world
    // points, so a moved head reads the map where it is, not where it rests.
    glm::mat4 modelToWorld{ 1.0f };
};

// `view` for a mesh placed by `modelToWorld` (a rigid transform, so normals turn with the view):
// the moving head is drawn by folding its transform into the view.
inline RenderView withModel(RenderView view, const glm::mat4& modelToWorld)
{
    view.view = view.view * modelToWorld;
    view.viewProjection = view.viewProjection * modelToWorld;
    view.modelToWorld = view.modelToWorld * modelToWorld;
    return view;
}

} // namespace wisp
