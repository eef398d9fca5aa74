#version 330 core
// Skin, cheaply: wrapped Lambert (light bleeds past the terminator as it does through skin, with a
// warm tint there), a cool fill from the other side, a sky/ground ambient, a soft rim that
// separates the silhouette from the background, and a faint broad sheen.
// With the growth overlay on, the skin's albedo is tinted by the painted weight (before lighting,
// so the head keeps its shape): a heat ramp from orange to magenta, colours no skin tone has.

in float v_keyShadow;
in float v_hairAmbient;
in vec3 v_positionView;
in vec3 v_normalView;
in float v_growthWeight;
in vec4 v_scalp;

uniform vec3 u_skinColour;  // linear RGB
uniform vec3 u_keyLightView;
uniform vec3 u_fillLightView;
uniform float u_growthOverlay;  // 1: tint by v_growthWeight; 0: plain skin (the weights may be unset)

out vec4 fragColour;

// Linear RGB. Weight 0 is plain skin; a little weight already shows clearly (orange), full weight
// is a saturated magenta.
vec3 growthTinted(vec3 skin, float weight)
{
    vec3 ramp = mix(vec3(1.0, 0.22, 0.01), vec3(0.80, 0.01, 0.75), weight);
    return mix(skin, ramp, 0.85 * smoothstep(0.0, 0.2, weight));
}

void main()
{
    // The scalp under the hair takes on the roots' colour (dyed scalp, as real grooms have), so the
    // parting and the crown read as hair, not as bare skin.
    vec3 albedo = mix(u_skinColour, v_scalp.rgb, 0.8 * smoothstep(0.0, 0.6, v_scalp.a));
    if (u_growthOverlay > 0.5)
        albedo = growthTinted(u_skinColour, clamp(v_growthWeight, 0.0, 1.0));

    vec3 N = normalize(v_normalView);
    vec3 V = normalize(-v_positionView);
    vec3 L = u_keyLightView;

    float nl = dot(N, L);
    const float wrap = 0.35;
    float key = max((nl + wrap) / (1.0 + wrap), 0.0);
    // The band just past the terminator reddens: light scattered under the skin.
    float scatter = max((nl + wrap) / (1.0 + wrap), 0.0) - max(nl, 0.0);
    float fill = max(dot(N, u_fillLightView), 0.0);
    // Sky above, darker ground below, in view space: the camera's up is close enough to the world's.
    float hemisphere = 0.5 + 0.5 * N.y;
    vec3 ambient = mix(vec3(0.10, 0.09, 0.09), vec3(0.22, 0.23, 0.26), hemisphere);

    // The hair's shadow and the head's own (looked up a little off the surface, so the skin does not
    // shadow itself where the map's texels are coarse), and the hair's density over the skin.
    float hairAmbient = v_hairAmbient;
    float shadow = v_keyShadow;
    ambient *= mix(0.35, 1.0, hairAmbient);
    vec3 colour = albedo * (vec3(1.0, 0.97, 0.93) * 0.95 * key * shadow + vec3(0.55, 0.6, 0.7) * 0.22 * fill * hairAmbient + ambient);
    colour += albedo * vec3(0.45, 0.08, 0.02) * scatter * shadow;
    // Powers by multiplication: pow() is a log and an exp per lane on a software rasteriser.
    float facing = 1.0 - max(dot(N, V), 0.0);
    float rim = facing * facing * facing;
    colour += vec3(0.30, 0.33, 0.38) * 0.35 * rim;
    vec3 H = normalize(L + V);
    float nh = max(dot(N, H), 0.0);
    float nh3 = nh * nh * nh;
    float nh6 = nh3 * nh3;
    float nh12 = nh6 * nh6;
    colour += vec3(0.04) * (nh12 * nh12) * shadow; // (N.H)^24

    fragColour = vec4(pow(clamp(colour, 0.0, 1.0), vec3(1.0 / 2.2)), 1.0);
}
