#version 330 core
// The software path's capture (widgets/HairRenderer.cpp, HairShading.h): what each sample of the
// drawn centre lines is whatever the view (strandWorld in hair_strand.glsl), captured by transform
// feedback once per frame, shadow map and level of detail; the CPU shades it for every view from
// there. a_ref: the sample's left-edge vertex (see widgets/HairStripLayout.h).

layout(location = 0) in uvec2 a_ref;

#include "hair_strand.glsl"

// Four texels per sample (HairWorldSample in widgets/HairShading.h).
out vec4 t_position;    // xyz world metres, w: along (0 root .. 1 tip)
out vec4 t_derivative;  // xyz world d position / d u, w: the key light reaching it
out vec4 t_root;        // rgb linear root colour (wetness applied), a: ambient
out vec4 t_tip;         // rgb linear tip colour, a: one hair's thickness at the root, metres; < 0: not drawn

void main()
{
    StrandWorld w = strandWorld(a_ref);
    t_position = vec4(w.position, w.along);
    t_derivative = vec4(w.derivative, w.keyShadow);
    t_root = vec4(w.rootColour, w.ambient);
    t_tip = vec4(w.tipColour, w.valid ? w.rootThicknessMetres : -1.0);
}
