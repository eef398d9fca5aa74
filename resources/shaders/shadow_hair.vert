#version 330 core
// A strand's point as seen from the key light (HairShadowMap): the coarse layout's vertices are
// the points themselves (one sample per segment), so no spline is evaluated here.
layout(location = 0) in uvec2 a_ref;  // see widgets/HairStripLayout.h

uniform samplerBuffer u_points;  // as in hair.vert: xyz world metres, w < 0.5 skips the strand
uniform mat4 u_lightViewProjection;
uniform mat4 u_worldToShadow;

out float v_depthMetres;  // from the light

void main()
{
    int segment = int(a_ref.y & 0xFFFu);
    float sampleIndex = float((a_ref.y >> 24) & 0x1Fu);
    int i = int(a_ref.x);
    vec4 q1 = texelFetch(u_points, i);
    if (q1.w < 0.5) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
        v_depthMetres = 0.0;
        return;
    }
    // Sample 0 is the segment's first point; the last sample (the tip vertex) its second.
    vec3 position = sampleIndex < 0.5 ? q1.xyz : texelFetch(u_points, i + 1).xyz;
    v_depthMetres = (u_worldToShadow * vec4(position, 1.0)).z;
    gl_Position = u_lightViewProjection * vec4(position, 1.0);
}
