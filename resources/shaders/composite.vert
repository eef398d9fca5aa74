#version 330 core
// A rectangle of the target given in clip space (FrameCompositor gives all of it), made from the
// vertex id as a four-vertex triangle strip: no vertex buffer. The fragment shader reads its pixel
// by gl_FragCoord.
uniform vec4 u_rect;  // x0, y0 (bottom left), x1, y1 (top right), clip space

void main()
{
    vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1));
    gl_Position = vec4(mix(u_rect.xy, u_rect.zw, corner), 0.0, 1.0);
}
