#version 330 core
// The key light and the hair's ambient at each of the head's vertices, captured by transform
// feedback (HeadRenderer) and read by head.vert as an attribute: the head's lookups run once per
// shadow map, not once per paint. Orbiting a paused scene (the key light fixed to the head) then
// costs the head no texture reads at all; on llvmpipe they were a third of the backdrop.
layout(location = 0) in vec3 a_position;  // model (head) space, metres
layout(location = 1) in vec3 a_normal;

uniform mat4 u_modelToWorld;    // model -> world: the shadow maps are in world space

out vec2 t_light;  // x: the key light reaching the vertex (1: no shadow); y: the ambient the hair around it leaves

#include "shadow_lookup.glsl"

void main()
{
    // Per vertex, not per pixel: the head's vertices are a few millimetres apart, finer than the
    // shadow map's texels, and a software rasteriser pays per pixel for every texture read. Looked
    // up a little off the surface, so the skin does not shadow itself where the texels are coarse.
    vec3 positionWorld = (u_modelToWorld * vec4(a_position, 1.0)).xyz;
    vec3 normalWorld = mat3(u_modelToWorld) * a_normal;
    float ambient;
    float key = keyLightFiltered(positionWorld + 0.004 * normalize(normalWorld), 0.004, ambient);
    t_light = vec2(key, ambient);
}
