#version 330 core
// One vertex of a strand: evaluates the uniform Catmull-Rom spline through the strand's points
// (the Cardinal spline of Lee et al. with tension 1/2) at this vertex's sample, shades it, and for
// ribbons pushes it sideways in screen space by half the ribbon's width (hair_strand.glsl). The
// points arrive each frame in a buffer texture; a_ref says which sample this vertex is (see
// widgets/HairStripLayout.h).

layout(location = 0) in uvec2 a_ref;

#include "hair_strand.glsl"

out vec4 v_colour;  // sRGB; alpha = coverage
// Ribbons: x runs -1 to 1 across the ribbon, y is half the drawn ribbon's width in pixels (its
// antialiasing skirt included); hair.frag turns them into the edge's coverage. Lines: (0, 1).
noperspective out vec2 v_edge;

void main()
{
    StrandSample s = strandSample(a_ref);
    float side = (a_ref.y & 0x80000000u) != 0u ? 1.0 : -1.0;
    gl_Position = s.clip + vec4(s.sideClip * side * s.clip.w, 0.0, 0.0);
    v_colour = s.colour;
    v_edge = u_ribbon > 0.5 ? vec2(side, s.halfExtentPixels) : vec2(0.0, 1.0);
}
