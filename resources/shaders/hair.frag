#version 330 core
// The hair is shaded per vertex (see hair.vert); alpha carries the strand's coverage of the ribbon,
// which blending turns into thickness (see HairRenderer::draw). Across a ribbon, the pixel's share
// of it: 1 inside, falling linearly to 0 over the last pixel of the drawn extent, which is half a
// pixel wider each side than the strand's drawn width, so the coverage summed across is that width
// (analytic antialiasing of a single-sampled frame; "phone-wire AA" with the width clamp, Persson 2012).
in vec4 v_colour;
noperspective in vec2 v_edge;
out vec4 fragColour;

void main()
{
    float fromCentrePixels = abs(v_edge.x) * v_edge.y;
    float edge = clamp(v_edge.y - fromCentrePixels, 0.0, 1.0);
    fragColour = vec4(v_colour.rgb, v_colour.a * edge);
}
