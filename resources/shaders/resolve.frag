#version 330 core
// Resolves the multisampled backdrop (background, head, grid; widgets/GlCanvas.h) into the
// single-sampled frame the hair is drawn into: colour averaged over each pixel's samples, depth the
// nearest sample's (so hair behind the head's edge stays hidden). One pass, as composite.frag does
// for the window: a software rasteriser's resolving blit costs several times this.
// The background's gradient is laid under the resolved colour here (u_gradient), not drawn into the
// multisampled target: the backdrop is cleared transparent and holds only the head and the grid
// (premultiplied), so the full-screen gradient costs one colour a pixel instead of four samples.
uniform sampler2DMS u_colour;
uniform sampler2DMS u_depth;
uniform int u_samples;
uniform float u_gradient;      // 1: the backdrop is over the gradient; 0: as it is
uniform vec3 u_top;            // sRGB, the gradient at the top edge
uniform vec3 u_bottom;         // sRGB, at the bottom edge
uniform float u_heightPixels;  // the target's height

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
    if (u_gradient > 0.5) {
        // As background.frag's full-screen triangle: 0 at the bottom edge, 1 at the top.
        vec3 under = mix(u_bottom, u_top, clamp(gl_FragCoord.y / u_heightPixels, 0.0, 1.0));
        fragColour = vec4(fragColour.rgb + (1.0 - fragColour.a) * under, 1.0);
    }
    gl_FragDepth = nearest;
}
