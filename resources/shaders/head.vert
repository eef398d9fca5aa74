#version 330 core
layout(location = 0) in vec3 a_position;  // model (head) space, metres
layout(location = 1) in vec3 a_normal;
layout(location = 2) in float a_growthWeight;  // 0..1, the painted growth map
layout(location = 3) in vec4 a_scalp;  // the root colour of the hair growing here (linear RGB), its weight

uniform mat4 u_view;            // model -> view (the head's transform folded in)
uniform mat4 u_viewProjection;
uniform mat4 u_modelToWorld;    // model -> world: the shadow maps are in world space

out float v_keyShadow;   // the key light reaching the vertex (1: no shadow)
out float v_hairAmbient; // the ambient light the hair around it leaves
out vec3 v_positionView;
out vec3 v_normalView;
out float v_growthWeight;
out vec4 v_scalp;

#include "shadow_lookup.glsl"

void main()
{
    // The head is rigid and unscaled: the view's rotation carries normals as it carries points.
    v_positionView = (u_view * vec4(a_position, 1.0)).xyz;
    v_normalView = mat3(u_view) * a_normal;
    v_growthWeight = a_growthWeight;
    v_scalp = a_scalp;
    // Per vertex, not per pixel: the head's vertices are a few millimetres apart, finer than the
    // shadow map's texels, and a software rasteriser pays per pixel for every texture read.
    vec3 positionWorld = (u_modelToWorld * vec4(a_position, 1.0)).xyz;
    vec3 normalWorld = mat3(u_modelToWorld) * a_normal;
    v_keyShadow = keyLightFiltered(positionWorld + 0.004 * normalize(normalWorld), 0.004, v_hairAmbient);
    gl_Position = u_viewProjection * vec4(a_position, 1.0);
}
