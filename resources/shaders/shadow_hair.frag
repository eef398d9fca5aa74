#version 330 core
// Pass 0: the fragment's depth (min-blended: the nearest hair or head per texel), green left far
// (it is the head's alone). Pass 1: the deep opacity map's layers (Yuksel & Keyser 2008): the
// fragment adds its opacity to every layer whose far end lies behind it (add-blended).
in float v_depthMetres;

uniform int u_pass;
uniform sampler2D u_depth;  // pass 0's result
uniform vec4 u_layerMetres;  // where the layers end, behind the nearest depth
uniform float u_strandOpacity;

out vec4 fragColour;

void main()
{
    if (u_pass == 0) {
        fragColour = vec4(v_depthMetres, 1e6, 0.0, 0.0);
        return;
    }
    float nearest = texelFetch(u_depth, ivec2(gl_FragCoord.xy), 0).r;
    float behind = v_depthMetres - nearest;
    fragColour = u_strandOpacity * vec4(lessThan(vec4(behind), u_layerMetres));
}
