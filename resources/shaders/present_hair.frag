#version 330 core
// composite.frag's single-sampled copy of the frame into the target (the window's back buffer, or
// the grab framebuffer), with the half-resolution hair (lowres_hair.glsl) laid over each pixel on
// the way: premultiplied "over", computed here rather than blended into the frame by a pass of its
// own. On a software rasteriser that pass cost as much as the hair's raster (12-14 ms between the
// editor's docks), though it only reads what this pass reads anyway.
#include "lowres_hair.glsl"

uniform sampler2D u_frameSingle;
uniform int u_keepAlpha;  // 1: write the frame's alpha; 0: opaque

out vec4 fragColour;

void main()
{
    vec4 colour = texelFetch(u_frameSingle, ivec2(gl_FragCoord.xy), 0);
    vec4 hair = lowResHairAt(gl_FragCoord.xy);
    colour = hair + colour * (1.0 - hair.a);
    fragColour = vec4(colour.rgb, u_keepAlpha == 1 ? colour.a : 1.0);
}
