#version 330 core
// Resolves the multisampled frame into the target (the window's back buffer), pixel for pixel: the
// average of each pixel's samples, as a resolving blit computes it, but in the same pass that
// writes the window (a software rasteriser's own resolve, then a copy, cost several times more).
// With u_samples 0 it copies a single-sampled frame instead (drawn without MSAA). Opaque: the hair
// leaves its coverage in alpha, which the screen would ignore anyway.
uniform sampler2DMS u_frame;
uniform sampler2D u_frameSingle;  // read instead when u_samples is 0
uniform int u_samples;            // of u_frame; 0: read u_frameSingle

out vec4 fragColour;

void main()
{
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec3 colour;
    if (u_samples == 0) {
        colour = texelFetch(u_frameSingle, pixel, 0).rgb;
    } else {
        vec3 sum = vec3(0.0);
        for (int i = 0; i < u_samples; ++i)
            sum += texelFetch(u_frame, pixel, i).rgb;
        colour = sum / float(u_samples);
    }
    fragColour = vec4(colour, 1.0);
}
