#version 330 core
// An image drawn over the frame (the heads-up line, the axis gizmo): a rectangle given in clip
// space, made from the vertex id as a four-vertex triangle strip.
uniform vec4 u_rect;  // x0, y0 (bottom left), x1, y1 (top right), clip space

out vec2 v_uv;

void main()
{
    vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1));
    v_uv = vec2(corner.x, 1.0 - corner.y);  // the image's first row is its top
    gl_Position = vec4(mix(u_rect.xy, u_rect.zw, corner), 0.0, 1.0);
}
