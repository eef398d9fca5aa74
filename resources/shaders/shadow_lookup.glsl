// The key light's deep opacity map (widgets/HairShadowMap.h), read by hair.vert and head_light.vert.
uniform float u_shadows;            // 1: read the maps; 0: everything fully lit
uniform mat4 u_worldToShadow;       // world -> (u, v, metres from the light)
uniform sampler2D u_shadowDepth;    // r: nearest hair or head; g: nearest head (metres from the light)
uniform sampler2D u_shadowOpacity;  // per layer: the opacity in front of its far end (mipmapped)
uniform vec4 u_shadowLayers;        // where the layers end, metres behind r

// The opacity in front of a point `behind` metres behind the nearest hair or head: linear between
// the layers' ends (Yuksel & Keyser 2008, sec. 4), the last layer's beyond it. `lod` > 0 reads a
// blurred level: the hair around the point as well as in front of it.
float opacityInFront(vec2 uv, float behind, float lod)
{
    vec4 layers = textureLod(u_shadowOpacity, uv, lod);
    vec4 ends = u_shadowLayers;
    if (behind <= 0.0)
        return 0.0;
    if (behind < ends.x)
        return layers.x * behind / ends.x;
    if (behind < ends.y)
        return mix(layers.x, layers.y, (behind - ends.x) / (ends.y - ends.x));
    if (behind < ends.z)
        return mix(layers.y, layers.z, (behind - ends.y) / (ends.z - ends.y));
    if (behind < ends.w)
        return mix(layers.z, layers.w, (behind - ends.z) / (ends.w - ends.z));
    return layers.w;
}

// The light through one texel of the maps to a point `depth` metres from the light.
float keyLightThroughTexel(ivec2 texel, float depth, float biasMetres)
{
    texel = clamp(texel, ivec2(0), textureSize(u_shadowDepth, 0) - 1);
    vec2 nearest = texelFetch(u_shadowDepth, texel, 0).rg;
    float behind = depth - biasMetres - nearest.r;
    vec2 uv = (vec2(texel) + 0.5) / vec2(textureSize(u_shadowDepth, 0));
    float head = smoothstep(0.006, 0.02, depth - biasMetres - nearest.g);
    return exp(-opacityInFront(uv, behind, 0.0)) * (1.0 - head);
}

// Where a world point falls in the maps: (u, v, metres from the light); false outside them (or
// without shadows), where everything is fully lit.
bool shadowCoordinates(vec3 worldPosition, out vec3 s)
{
    s = (u_worldToShadow * vec4(worldPosition, 1.0)).xyz;
    return u_shadows > 0.5 && all(greaterThanEqual(s.xy, vec2(0.0))) && all(lessThanEqual(s.xy, vec2(1.0)));
}

// keyLight() filtered: the four texels around the point, weighted bilinearly (percentage-closer
// filtering), so the head's and the hair's shadow edges on the skin are soft, not the map's
// squares. Four times the reads, and the ambient term from the blurred level: for the head's
// vertices, not the hair's many.
float keyLightFiltered(vec3 worldPosition, float biasMetres, out float ambient)
{
    ambient = 1.0;
    vec3 s;
    if (!shadowCoordinates(worldPosition, s))
        return 1.0;
    vec2 texelPosition = s.xy * vec2(textureSize(u_shadowDepth, 0)) - 0.5;
    ivec2 base = ivec2(floor(texelPosition));
    vec2 f = texelPosition - vec2(base);
    float light = mix(mix(keyLightThroughTexel(base, s.z, biasMetres), keyLightThroughTexel(base + ivec2(1, 0), s.z, biasMetres), f.x),
                      mix(keyLightThroughTexel(base + ivec2(0, 1), s.z, biasMetres), keyLightThroughTexel(base + ivec2(1, 1), s.z, biasMetres), f.x),
                      f.y);
    float nearest = textureLod(u_shadowDepth, s.xy, 0.0).r;
    ambient = exp(-0.35 * opacityInFront(s.xy, s.z - biasMetres - nearest, 2.0));
    return light;
}

// The key light reaching a world point, 0..1: the hair's transmittance exp(-opacity) (Kim &
// Neumann 2001), times nothing where the head stands between the point and the light. `ambient`
// gets the light the hair around the point leaves for the soft ambient term (denser hair, deeper
// in: darker). `biasMetres` keeps a surface from shadowing itself. One read of each map, at the
// once-blurred level (mip 1, two texels): the hair's vertices are many, and a software rasteriser
// pays for every fetch in them.
float keyLight(vec3 worldPosition, float biasMetres, out float ambient)
{
    ambient = 1.0;
    vec3 s;
    if (!shadowCoordinates(worldPosition, s))
        return 1.0;
    vec2 nearest = textureLod(u_shadowDepth, s.xy, 0.0).rg;
    float opacity = opacityInFront(s.xy, s.z - biasMetres - nearest.r, 1.0);
    ambient = exp(-0.35 * opacity);
    float head = smoothstep(0.006, 0.02, s.z - biasMetres - nearest.g);
    return exp(-opacity) * (1.0 - head);
}
