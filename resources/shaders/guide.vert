#version 330 core
// Scene guides (ground grid, wind arrow, brush rings): coloured geometry in world space.
layout(location = 0) in vec3 a_position;  // world, metres
layout(location = 1) in vec3 a_normal;    // zero for lines
layout(location = 2) in vec4 a_colour;    // sRGB, alpha

uniform mat4 u_view;
uniform mat4 u_viewProjection;

out vec3 v_positionWorld;
out vec3 v_normalView;
out vec4 v_colour;

void main()
{
    v_positionWorld = a_position;
    v_normalView = mat3(u_view) * a_normal;
    v_colour = a_colour;
    gl_Position = u_viewProjection * vec4(a_position, 1.0);
}
