#version 330 core
in vec2 v_uv;
uniform sampler2D u_image;  // premultiplied alpha, as QPainter paints it

out vec4 fragColour;

void main()
{
    fragColour = texture(u_image, v_uv);
}
