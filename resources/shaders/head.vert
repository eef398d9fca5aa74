#version 330 core
layout(location = 0) in vec3 a_position;  // world, metres
layout(location = 1) in vec3 a_normal;
layout(location = 2) in float a_growthWeight;  // 0..1, the painted growth map

uniform mat4 u_view;
uniform mat4 u_viewProjection;

out vec3 v_positionWorld;
out vec3 v_normalWorld;
out vec3 v_positionView;
out vec3 v_normalView;
out float v_growthWeight;

void main()
{
    // The head is rigid and unscaled: the view's rotation carries normals as it carries points.
    v_positionView = (u_view * vec4(a_position, 1.0)).xyz;
    v_normalView = mat3(u_view) * a_normal;
    v_growthWeight = a_growthWeight;
    v_positionWorld = a_position;
    v_normalWorld = a_normal;
    gl_Position = u_viewProjection * vec4(a_position, 1.0);
}
