#version 330 core
// Resolves the multisampled backdrop (background, head, grid; widgets/GlCanvas.h) into the
// single-sampled frame the hair is drawn into: colour averaged over each pixel's samples, depth the
// nearest sample's (so hair behind the head's edge stays hidden). One pass, as composite.frag does
// for the window: a software rasteriser's resolving blit costs several times this.
uniform sampler2DMS u_colour;
uniform sampler2DMS u_depth;
uniform int u_samples;

out vec4 fragColour;

void main()
{
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 sum = vec4(0.0);
    float nearest = 1.0;
    for (int i = 0; i < u_samples; ++i) {
        sum += texelFetch(u_colour, pixel, i);
        nearest = min(nearest, texelFetch(u_depth, pixel, i).r);
    }
    fragColour = sum / float(max(u_samples, 1));
    gl_FragDepth = nearest;
}
