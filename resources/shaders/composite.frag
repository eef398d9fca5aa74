#version 330 core
// Resolves the multisampled frame into the target (the window's back buffer), pixel for pixel: the
// average of each pixel's samples, as a resolving blit computes it, but in the same pass that
// writes the window (a software rasteriser's own resolve, then a copy, cost several times more).
// With u_samples 0 it copies a single-sampled frame instead (drawn without MSAA). Opaque: the hair
// leaves its coverage in alpha, which the screen would ignore anyway. u_keepAlpha 1 keeps the
// average alpha instead (a rendered image with a transparent background: the frame was cleared to
// 0 and holds premultiplied colour, so averaging samples is right for both).
uniform sampler2DMS u_frame;
uniform sampler2D u_frameSingle;  // read instead when u_samples is 0
uniform int u_samples;            // of u_frame; 0: read u_frameSingle
uniform int u_keepAlpha;          // 1: write the frame's alpha; 0: opaque

out vec4 fragColour;

void main()
{
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 colour;
    if (u_samples == 0) {
        colour = texelFetch(u_frameSingle, pixel, 0);
    } else {
        vec4 sum = vec4(0.0);
        for (int i = 0; i < u_samples; ++i)
            sum += texelFetch(u_frame, pixel, i);
        colour = sum / float(u_samples);
    }
    fragColour = vec4(colour.rgb, u_keepAlpha == 1 ? colour.a : 1.0);
}
