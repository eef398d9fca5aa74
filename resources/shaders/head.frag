#version 330 core
// Skin, cheaply: wrapped Lambert (light bleeds past the terminator as it does through skin, with a
// warm tint there), a cool fill from the other side, a sky/ground ambient, a soft rim that
// separates the silhouette from the background, and a faint broad sheen.

in vec3 v_positionView;
in vec3 v_normalView;

uniform vec3 u_skinColour;  // linear RGB
uniform vec3 u_keyLightView;
uniform vec3 u_fillLightView;

out vec4 fragColour;

void main()
{
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

    vec3 colour = u_skinColour * (vec3(1.0, 0.97, 0.93) * 0.95 * key + vec3(0.55, 0.6, 0.7) * 0.22 * fill + ambient);
    colour += u_skinColour * vec3(0.45, 0.08, 0.02) * scatter;
    float rim = pow(1.0 - max(dot(N, V), 0.0), 3.0);
    colour += vec3(0.30, 0.33, 0.38) * 0.35 * rim;
    vec3 H = normalize(L + V);
    colour += vec3(0.04) * pow(max(dot(N, H), 0.0), 24.0);

    fragColour = vec4(pow(clamp(colour, 0.0, 1.0), vec3(1.0 / 2.2)), 1.0);
}
