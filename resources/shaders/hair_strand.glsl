// Included by hair.vert and hair_samples.vert (shaderSource in widgets/GlSupport.cpp).
// One vertex of a strand: evaluates the uniform Catmull-Rom spline through the strand's points
// (the Cardinal spline of Lee et al. with tension 1/2) at this vertex's sample, shades it, and for
// ribbons pushes it sideways in screen space by half the ribbon's width. The points arrive each
// frame in a buffer texture; a_ref says which sample this vertex is (see widgets/HairStripLayout.h).

// xyz: world position, metres; w: 0 to skip the strand (a non-finite point), 1 for the style's
// colours (u_rootColour, u_tipColour), 2 + k for look k of u_looks; plus 0.45 times the strand's
// wetness (wet hair is darker).
uniform samplerBuffer u_points;
uniform samplerBuffer u_looks;   // look k: texel 2k its root colour (alpha: its hair thickness, metres, or 0),
                                 // 2k + 1 its tip colour (linear RGB)
uniform mat4 u_view;
uniform mat4 u_projection;
uniform vec2 u_viewportPixels;
uniform float u_samplesPerSegment;
uniform float u_ribbon;           // 1: camera-facing ribbon; 0: line (no sideways offset)
uniform float u_hairThicknessMetres;  // one hair at the root, for strands without a look (or whose look has none)
uniform float u_widthScale;          // a drawn strand stands for a lock of hairs, so it is wider than one hair
uniform float u_tipThicknessRatio;   // the tip's thickness over the root's
uniform float u_minWidthPixels;   // narrower strands are drawn this wide and fainter (coverage)

uniform vec3 u_rootColour;  // linear RGB, for strands without a look
uniform vec3 u_tipColour;   // linear RGB
uniform vec3 u_keyLightView;
uniform vec3 u_fillLightView;
uniform vec3 u_headCentreView;
uniform float u_tipFade;  // how much the strand fades out toward the tip, 0..1

#include "shadow_lookup.glsl"

// Shaded here, per vertex, not per fragment: a software rasteriser pays setup work for every
// interpolated value of each of the ~200k thin primitives, and across a strand a pixel or two wide
// the shading is constant anyway. Along the strand, samples are a few pixels apart.

float kajiyaKaySpecular(vec3 tangent, vec3 halfVector, float exponent)
{
    float th = dot(tangent, halfVector);
    float sinTH = sqrt(max(1.0 - th * th, 0.0));
    return pow(sinTH, exponent) * smoothstep(-1.0, 0.0, th);
}

// Kajiya-Kay hair shading: a strand is a thin cylinder, so its diffuse term is sin(T, L) and its
// highlight peaks where the half vector is perpendicular to the tangent. Two highlights, as in
// Scheuermann's practical take on Marschner's model: a whitish one shifted toward the tip and a
// broader one tinted with the hair's colour shifted toward the root. The head gives the hair a
// volume normal, so hair on the side away from the light falls into shadow.
// `keyShadow`: the key light that reaches the point (the deep opacity map), `ambient`: what the hair
// around it leaves of the ambient light; both 1 without shadows.
vec3 shadeHair(vec3 positionView, vec3 T, float along, vec3 rootColour, vec3 tipColour, float keyShadow, float ambient)
{
    vec3 V = normalize(-positionView);
    vec3 L = u_keyLightView;
    // The strand's normal facing the viewer: the view direction made perpendicular to the strand.
    vec3 N = V - T * dot(T, V);
    N = dot(N, N) > 1e-8 ? normalize(N) : V;

    vec3 base = mix(rootColour, tipColour, smoothstep(0.0, 1.0, along));
    float tl = dot(T, L);
    float diffuse = sqrt(max(1.0 - tl * tl, 0.0));
    // Wrapped, so the shadow side is dim but never black (light scatters through hair).
    vec3 volumeNormal = normalize(positionView - u_headCentreView + vec3(1e-6));
    float keyWrap = clamp((dot(volumeNormal, L) + 0.5) / 1.5, 0.0, 1.0);
    float fillWrap = clamp((dot(volumeNormal, u_fillLightView) + 0.5) / 1.5, 0.0, 1.0);
    // Hair near the scalp sits under the hair above it: without the maps, a guess from the position
    // along the strand; with them, the hair's density around the point.
    float occlusion = u_shadows > 0.5 ? mix(0.3, 1.0, ambient) : mix(0.45, 1.0, smoothstep(0.0, 0.4, along));

    vec3 H = normalize(L + V);
    float primary = kajiyaKaySpecular(normalize(T + 0.08 * N), H, 90.0);
    float secondary = kajiyaKaySpecular(normalize(T - 0.12 * N), H, 22.0);

    float key = keyWrap * keyShadow;
    vec3 colour = base * ((0.18 + 0.25 * fillWrap) * occlusion + 0.95 * diffuse * key);
    colour += key * (0.28 * primary * vec3(1.0, 0.97, 0.92) + 0.35 * secondary * base);
    return pow(clamp(colour, 0.0, 1.0), vec3(1.0 / 2.2));
}

// What a spline sample of a strand is whatever the view: where it lies, which way the strand runs,
// how far along it, its colours and thickness, and the key light reaching it. The software path
// captures this once per frame and shadow map (hair_sample_world.vert) and does the view's part on
// the CPU (widgets/HairShading.h, which follows strandSample below line for line).
struct StrandWorld {
    bool valid;          // false: the strand has a non-finite point
    vec3 position;       // world, metres
    vec3 derivative;     // world, d position / d u (u: 0..1 over the segment)
    float along;         // 0 at the root, 1 at the tip
    vec3 rootColour;     // linear RGB, darkened by the strand's wetness
    vec3 tipColour;
    float rootThicknessMetres;  // one hair at the root: the look's, or u_hairThicknessMetres
    float keyShadow;     // keyLight(): 1 without shadows
    float ambient;
};

StrandWorld strandWorld(uvec2 ref)
{
    StrandWorld w;
    int segment = int(ref.y & 0xFFFu);
    int segments = int((ref.y >> 12) & 0xFFFu);
    float sampleIndex = float((ref.y >> 24) & 0x1Fu);
    int i = int(ref.x);

    vec4 q1 = texelFetch(u_points, i);
    vec4 q2 = texelFetch(u_points, i + 1);
    w.valid = q1.w >= 0.5;
    if (!w.valid) {
        w.position = vec3(0.0);
        w.derivative = vec3(0.0, 1.0, 0.0);
        w.along = 0.0;
        w.rootColour = vec3(0.0);
        w.tipColour = vec3(0.0);
        w.rootThicknessMetres = 0.0;
        w.keyShadow = 1.0;
        w.ambient = 1.0;
        return w;
    }
    vec3 p1 = q1.xyz;
    vec3 p2 = q2.xyz;
    // At the ends, mirror the neighbour (a phantom point), which makes the end tangent follow the
    // first or last segment instead of curling.
    vec3 p0 = segment > 0 ? texelFetch(u_points, i - 1).xyz : 2.0 * p1 - p2;
    vec3 p3 = segment + 1 < segments ? texelFetch(u_points, i + 2).xyz : 2.0 * p2 - p1;

    float u = sampleIndex / u_samplesPerSegment;
    vec3 c1 = p2 - p0;
    vec3 c2 = 2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3;
    vec3 c3 = -p0 + 3.0 * p1 - 3.0 * p2 + p3;
    w.position = p1 + 0.5 * u * (c1 + u * (c2 + u * c3));
    w.derivative = 0.5 * (c1 + u * (2.0 * c2 + u * 3.0 * c3));
    if (dot(w.derivative, w.derivative) < 1e-16)
        w.derivative = p2 - p1;
    w.along = (float(segment) + u) / float(max(segments, 1));

    int look = int(q1.w + 0.5) - 2;
    vec4 lookRoot = look >= 0 ? texelFetch(u_looks, 2 * look) : vec4(u_rootColour, 0.0);
    w.rootThicknessMetres = lookRoot.a > 0.0 ? lookRoot.a : u_hairThicknessMetres;
    vec3 rootColour = lookRoot.rgb;
    vec3 tipColour = look >= 0 ? texelFetch(u_looks, 2 * look + 1).rgb : u_tipColour;
    // Water fills the gaps between the cuticle scales: wet hair reflects less diffusely and looks
    // darker (about half as bright soaked).
    float wetness = clamp((q1.w - float(look + 2)) / 0.45, 0.0, 1.0);
    w.rootColour = rootColour * (1.0 - 0.5 * wetness);
    w.tipColour = tipColour * (1.0 - 0.5 * wetness);
    w.keyShadow = keyLight(w.position, 0.002, w.ambient);
    return w;
}

// One spline sample of a strand, both edges of a ribbon at once (the vertex shader runs per edge
// or, through hair_samples.vert, once per sample): `clip` the centre line's clip position;
// `sideClip` what one edge adds to clip.xy per unit of clip.w (the other edge subtracts it; zero for
// lines); `halfExtentPixels` half the drawn ribbon's width, its antialiasing skirt included (1 for
// lines); `colour` sRGB with the coverage in alpha. `ref` as a_ref in hair.vert.
struct StrandSample {
    vec4 clip;
    vec2 sideClip;
    float halfExtentPixels;
    vec4 colour;
};

StrandSample strandSample(uvec2 ref)
{
    StrandSample result;
    StrandWorld w = strandWorld(ref);
    if (!w.valid) {
        // A strand with a non-finite point: put every vertex of it outside the clip volume, so all
        // its primitives are clipped away.
        result.clip = vec4(2.0, 2.0, 2.0, 1.0);
        result.sideClip = vec2(0.0);
        result.halfExtentPixels = 1.0;
        result.colour = vec4(0.0);
        return result;
    }
    vec4 positionView = u_view * vec4(w.position, 1.0);
    vec3 tangentView = mat3(u_view) * w.derivative;
    float tangentLength = length(tangentView);
    tangentView = tangentLength > 1e-12 ? tangentView / tangentLength : vec3(0.0, 1.0, 0.0);

    float along = w.along;
    float depth = max(-positionView.z, 1e-4);
    float rootWidthMetres = w.rootThicknessMetres * u_widthScale;
    float widthMetres = rootWidthMetres * mix(1.0, u_tipThicknessRatio, along);
    // Pixels per metre at this depth: projection[1][1] = 1 / tan(fovY / 2).
    float widthPixels = widthMetres * u_projection[1][1] * 0.5 * u_viewportPixels.y / depth;
    float drawnPixels = max(widthPixels, u_minWidthPixels);

    vec4 clip = u_projection * positionView;
    result.sideClip = vec2(0.0);
    result.halfExtentPixels = 1.0;
    if (u_ribbon > 0.5) {
        // The strand's direction on screen: project a point a little way along the tangent. The
        // step scales with depth so both points stay in front of the camera and apart in float.
        vec4 clipAhead = u_projection * (positionView + vec4(tangentView * (1e-3 * depth), 0.0));
        vec2 screen = clip.xy / clip.w * u_viewportPixels;
        vec2 screenAhead = clipAhead.xy / clipAhead.w * u_viewportPixels;
        vec2 direction = screenAhead - screen;
        float directionLength = length(direction);
        // A strand pointing straight at the camera has no direction on screen: any normal will do.
        direction = directionLength > 1e-6 ? direction / directionLength : vec2(1.0, 0.0);
        vec2 normal = vec2(-direction.y, direction.x);
        // Half a pixel more on each side, where hair.frag fades the edge out (the frame the hair
        // is drawn into is single-sampled: this is its antialiasing). NDC spans 2 units over the
        // viewport, and clip space is NDC times w.
        float extentPixels = drawnPixels + 1.0;
        result.sideClip = normal * extentPixels / u_viewportPixels;
        result.halfExtentPixels = 0.5 * extentPixels;
    }
    result.clip = clip;

    float coverage = min(widthPixels / drawnPixels, 1.0);
    float alpha = coverage * (1.0 - u_tipFade * smoothstep(0.55, 1.0, along));
    result.colour = vec4(shadeHair(positionView.xyz, tangentView, along, w.rootColour, w.tipColour, w.keyShadow, w.ambient), alpha);
    return result;
}
