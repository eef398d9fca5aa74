#version 330 core
// A vertical gradient, as DCC viewports have: it reads as depth and keeps dark hair visible.
in float v_height;
uniform vec3 u_top;     // sRGB
uniform vec3 u_bottom;  // sRGB
out vec4 fragColour;

void main()
{
    fragColour = vec4(mix(u_bottom, u_top, clamp(v_height, 0.0, 1.0)), 1.0);
}
