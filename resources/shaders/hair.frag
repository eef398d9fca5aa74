#version 330 core
// The hair is shaded per vertex (see hair.vert); alpha carries the strand's coverage of the ribbon,
// which blending turns into thickness (see HairRenderer::draw).
in vec4 v_colour;
out vec4 fragColour;

void main()
{
    fragColour = v_colour;
}
