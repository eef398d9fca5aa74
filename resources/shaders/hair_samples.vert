#version 330 core
// The ribbons' first pass (widgets/HairRenderer.cpp): each spline sample evaluated and shaded once,
// captured by transform feedback, instead of once for each of the ribbon's two edges. A software
// rasteriser runs vertex shaders on one thread, and this shader is most of the hair's cost there.
// a_ref: a sample's left-edge vertex (see widgets/HairStripLayout.h).

layout(location = 0) in uvec2 a_ref;

#include "hair_strand.glsl"

// Three texels per sample of the buffer hair_ribbon.vert reads.
out vec4 t_clip;
out vec4 t_colour;
out vec4 t_side;  // xy: sideClip, z: halfExtentPixels

void main()
{
    StrandSample s = strandSample(a_ref);
    t_clip = s.clip;
    t_colour = s.colour;
    t_side = vec4(s.sideClip, s.halfExtentPixels, 0.0);
}
