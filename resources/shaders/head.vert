#version 330 core
layout(location = 0) in vec3 a_position;  // world, metres
layout(location = 1) in vec3 a_normal;

uniform mat4 u_view;
uniform mat4 u_viewProjection;

out vec3 v_positionView;
out vec3 v_normalView;

void main()
{
    // The head is rigid and unscaled: the view's rotation carries normals as it carries points.
    v_positionView = (u_view * vec4(a_position, 1.0)).xyz;
    v_normalView = mat3(u_view) * a_normal;
    gl_Position = u_viewProjection * vec4(a_position, 1.0);
}
