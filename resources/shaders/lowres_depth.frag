#version 330 core
// The half-resolution hair target's starting depth (widgets/HairLowResTarget.h): the farthest of the
// frame's 2x2 block under this texel, so hair is drawn where it is in front of the backdrop in any
// of the four pixels (the composite decides per pixel) and rejected where it is behind in all.
uniform sampler2D u_frameDepth;
uniform ivec2 u_framePixels;

out vec4 fragColour;

void main()
{
    ivec2 first = 2 * ivec2(gl_FragCoord.xy);
    ivec2 last = min(first + 1, u_framePixels - 1);
    float farthest = max(max(texelFetch(u_frameDepth, first, 0).r, texelFetch(u_frameDepth, ivec2(last.x, first.y), 0).r),
        max(texelFetch(u_frameDepth, ivec2(first.x, last.y), 0).r, texelFetch(u_frameDepth, last, 0).r));
    fragColour = vec4(0.0);
    gl_FragDepth = farthest;
}
