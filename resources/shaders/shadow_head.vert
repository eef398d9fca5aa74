#version 330 core
// The head (or the body) as seen from the key light: its depth only (HairShadowMap's first pass).
layout(location = 0) in vec3 a_position;  // model (head) space, metres

uniform mat4 u_lightViewProjection;
uniform mat4 u_worldToShadow;
uniform mat4 u_modelToWorld;  // where the frame has the head (Frame::headToWorld)

out float v_depthMetres;

void main()
{
    vec4 world = u_modelToWorld * vec4(a_position, 1.0);
    v_depthMetres = (u_worldToShadow * world).z;
    gl_Position = u_lightViewProjection * world;
}
