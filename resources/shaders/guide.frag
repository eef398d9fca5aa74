#version 330 core
in vec3 v_positionWorld;
in vec3 v_normalView;
in vec4 v_colour;

uniform float u_lit;          // 1: shade by the key light (solids); 0: flat (lines)
uniform vec3 u_keyLightView;
uniform vec3 u_fadeCentre;    // world, metres
uniform float u_fadeRadius;   // metres; lines fade out toward this distance (0: no fade)
uniform float u_alphaScale;   // 1 normally; the brush ring's hidden parts are drawn fainter

out vec4 fragColour;

void main()
{
    vec3 colour = v_colour.rgb;
    float alpha = v_colour.a;
    if (u_lit > 0.5) {
        vec3 N = normalize(v_normalView);
        float key = max((dot(N, u_keyLightView) + 0.4) / 1.4, 0.0);
        colour *= 0.35 + 0.75 * key;
    }
    if (u_fadeRadius > 0.0) {
        float d = length(v_positionWorld.xz - u_fadeCentre.xz);
        alpha *= 1.0 - smoothstep(0.35 * u_fadeRadius, u_fadeRadius, d);
    }
    fragColour = vec4(colour, alpha * u_alphaScale);
}
