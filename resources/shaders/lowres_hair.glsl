// The half-resolution hair at one frame pixel (widgets/HairLowResTarget.h): premultiplied colour
// and alpha, vec4(0) where there is none. Shared by the pass that blends it over the frame
// (lowres_composite.frag) and the pass that finishes the frame with it laid in (present_hair.frag).
//
// Each frame pixel takes the four target texels around it with bilinear weights, so a strand's
// coverage summed across it is what it was (a thin strand spreads over about two pixels, no fainter
// in total). The target's depth is the farthest backdrop of its 2x2 block (the hair does not write
// it: see HairLowResTarget.h); a texel whose block reaches more than 1 % behind this pixel's backdrop
// straddles a silhouette this pixel is in front of, and gives nothing here, so hair behind the
// head's edge stays behind it.
uniform sampler2D u_hair;        // the target's colour
uniform sampler2D u_hairDepth;   // the target's depth: each 2x2 block's farthest backdrop
uniform sampler2D u_frameDepth;  // the frame's depth (read only)
uniform vec2 u_framePixels;
uniform vec2 u_hairPixels;
uniform vec4 u_hairRegion; // x0, y0, x1, y1 in clip space: where the target was drawn this frame
uniform float u_p22;  // projection[2][2] and [3][2]: window depth to distance
uniform float u_p32;

float distanceMetres(float windowDepth)
{
    // z_ndc = (P22 z + P32) / -z, so -z = P32 / (z_ndc + P22).
    return u_p32 / (2.0 * windowDepth - 1.0 + u_p22);
}

vec4 lowResHairAt(vec2 fragCoord)
{
    // Outside the region the target keeps texels of earlier frames.
    vec2 clip = fragCoord / u_framePixels * 2.0 - 1.0;
    if (any(lessThan(clip, u_hairRegion.xy)) || any(greaterThan(clip, u_hairRegion.zw)))
        return vec4(0.0);
    // This pixel's centre in target texels, less half a texel: the four around it and its weights.
    vec2 at = fragCoord * (u_hairPixels / u_framePixels) - 0.5;
    vec2 base = floor(at);
    vec2 f = at - base;
    ivec2 last = ivec2(u_hairPixels) - 1;
    vec4 texels[4];
    vec4 any = vec4(0.0);
    for (int k = 0; k < 4; ++k) {
        texels[k] = texelFetch(u_hair, clamp(ivec2(base) + ivec2(k & 1, k >> 1), ivec2(0), last), 0);
        any += texels[k];
    }
    // No hair around this pixel (most of the frame): no depths to read.
    if (dot(any, vec4(1.0)) <= 0.0)
        return vec4(0.0);
    float backdrop = distanceMetres(texelFetch(u_frameDepth, ivec2(fragCoord), 0).r);
    vec4 sum = vec4(0.0);
    float weights = 0.0;
    for (int k = 0; k < 4; ++k) {
        ivec2 offset = ivec2(k & 1, k >> 1);
        ivec2 texel = clamp(ivec2(base) + offset, ivec2(0), last);
        vec2 w2 = mix(1.0 - f, f, vec2(offset));
        float blockDistance = distanceMetres(texelFetch(u_hairDepth, texel, 0).r);
        float weight = blockDistance <= backdrop * 1.01 ? w2.x * w2.y : 0.0;
        sum += weight * texels[k];
        weights += weight;
    }
    // Renormalised over the texels that count: at a silhouette the hair in front of the head keeps
    // its strength on the head's side.
    return weights > 0.0 ? sum / weights : vec4(0.0);
}
