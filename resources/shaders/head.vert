#version 330 core
layout(location = 0) in vec3 a_position;  // model (head) space, metres
layout(location = 1) in vec3 a_normal;
layout(location = 2) in float a_growthWeight;  // 0..1, the painted growth map
layout(location = 3) in vec4 a_scalp;  // the root colour of the hair growing here (linear RGB), its weight
layout(location = 4) in vec2 a_light;  // the key light reaching the vertex, the hair's ambient (head_light.vert)

uniform mat4 u_view;            // model -> view (the head's transform folded in)
uniform mat4 u_viewProjection;

out float v_keyShadow;   // the key light reaching the vertex (1: no shadow)
out float v_hairAmbient; // the ambient light the hair around it leaves
out vec3 v_positionView;
out vec3 v_normalView;
out float v_growthWeight;
out vec4 v_scalp;

void main()
{
    // The head is rigid and unscaled: the view's rotation carries normals as it carries points.
    v_positionView = (u_view * vec4(a_position, 1.0)).xyz;
    v_normalView = mat3(u_view) * a_normal;
    v_growthWeight = a_growthWeight;
    v_scalp = a_scalp;
    v_keyShadow = a_light.x;
    v_hairAmbient = a_light.y;
    gl_Position = u_viewProjection * vec4(a_position, 1.0);
}
