#version 330 core
// The head (or the body) as seen from the key light: its depth only (HairShadowMap's first pass).
layout(location = 0) in vec3 a_position;  // world, metres

uniform mat4 u_lightViewProjection;
uniform mat4 u_worldToShadow;

out float v_depthMetres;

void main()
{
    v_depthMetres = (u_worldToShadow * vec4(a_position, 1.0)).z;
    gl_Position = u_lightViewProjection * vec4(a_position, 1.0);
}
