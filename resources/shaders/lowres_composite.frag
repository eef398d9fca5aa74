#version 330 core
// Lays the half-resolution hair over the full-resolution frame (widgets/HairLowResTarget.h), blended
// "over": source ONE, destination ONE_MINUS_SRC_ALPHA. Used where something is drawn over the hair
// afterwards (the brush rings); otherwise present_hair.frag lays it in while finishing the frame.
#include "lowres_hair.glsl"

out vec4 fragColour;

void main()
{
    vec4 hair = lowResHairAt(gl_FragCoord.xy);
    // A software rasteriser skips the rest of a block whose fragments all end here.
    if (hair == vec4(0.0))
        discard;
    fragColour = hair;
}
