#version 330 core
// The ribbons' second pass: one edge vertex of a sample hair_samples.vert evaluated. The index
// drawn is the layout's vertex (widgets/HairStripLayout.h): sample index / 2, the right edge when
// odd; the samples buffer is captured for the drawn strands' vertices in the same order.

uniform samplerBuffer u_samples;  // three texels per sample: clip, colour, (sideClip, halfExtentPixels)

out vec4 v_colour;
noperspective out vec2 v_edge;

void main()
{
    int sampleIndex = gl_VertexID >> 1;
    float side = (gl_VertexID & 1) != 0 ? 1.0 : -1.0;
    vec4 clip = texelFetch(u_samples, 3 * sampleIndex);
    vec4 sideTexel = texelFetch(u_samples, 3 * sampleIndex + 2);
    gl_Position = clip + vec4(sideTexel.xy * side * clip.w, 0.0, 0.0);
    v_colour = texelFetch(u_samples, 3 * sampleIndex + 1);
    v_edge = vec2(side, sideTexel.z);
}
