#version 330 core
// Min-blended: red the nearest hair or head, green the nearest head.
in float v_depthMetres;
out vec4 fragColour;

void main()
{
    fragColour = vec4(v_depthMetres, v_depthMetres, 0.0, 0.0);
}
