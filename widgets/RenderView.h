#pragma once
// What a renderer needs to know about the view it draws into: one value per frame, filled by the
// viewport from its camera, so renderers never read the camera or the widget themselves.

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace wisp {

struct RenderView {
    glm::mat4 view{ 1.0f };
    glm::mat4 projection{ 1.0f };
    glm::mat4 viewProjection{ 1.0f };
    glm::vec2 viewportPixels{ 1.0f }; // framebuffer size in device pixels
    // Lighting is a head-lamp rig fixed to the camera (as DCC viewports do), so the key light
    // always models what the artist looks at. Unit vectors toward the lights, view space.
    glm::vec3 keyLightView{ 0.0f, 0.0f, 1.0f };
    glm::vec3 fillLightView{ 0.0f, 0.0f, 1.0f };
    glm::vec3 headCentreView{ 0.0f }; // the head's centre in view space, metres (hair's volume normals)
    float headRadiusMetres = 0.1f;
    int samples = 0; // MSAA samples of the target framebuffer (0 or 1: none)
};

} // namespace wisp
