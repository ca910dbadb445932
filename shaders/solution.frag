#version 450 core
// Solution view: the interpolated smooth value, or the leaf's own value (flat), with optional
// leaf-edge lines and optional display tone mapping. Output is linear unless tone_map is on.

in vec3 v_colour;
in vec3 v_grid;
in vec2 v_st;

layout(location = 0) out vec4 out_colour;

layout(location = 1) uniform int flat_shading; // 1: flat, 0: smooth
layout(location = 2) uniform int patch_edges;  // 1: darken leaf edges
layout(location = 3) uniform float scale;      // multiplies every value (display only)
layout(location = 4) uniform int tone_map;     // 1: Reinhard + sRGB encode (for a window)
layout(location = 5) uniform float reinhard_white; // white point in scaled units
// Highlight pass (RenderOptions::highlight): alpha > 0 writes this colour as is, unscaled.
layout(location = 6) uniform vec4 highlight;
// Textured draws (smooth radiosity): v_colour is rho (E + ambient); the value shown is
// Be + texel * v_colour, the texel's linear reflectance (trilinear through the mipmap).
layout(location = 7) uniform int textured;
layout(location = 8) uniform vec3 emitted;      // Be of the draw's material [W unit^-2]
layout(location = 9) uniform uint primitive_base; // first triangle of this draw in triangle_leaf
layout(binding = 0) uniform sampler2D reflectance_map;

// Flat values: the leaf of each triangle (gl_PrimitiveID counts triangles from the start of the
// single draw call), and RGB per leaf [W unit^-2], rewritten every frame.
layout(std430, binding = 3) readonly buffer TriangleLeaf { uint triangle_leaf[]; };
layout(std430, binding = 4) readonly buffer LeafColours { float leaf_rgb[]; };

// Distance in pixels from this fragment to the nearest leaf edge: grid lines u n = i, v n = j,
// and for triangles u n + v n = k (the lattice of midpoint subdivision).
float edge_distance_pixels() {
    // Derivatives outside any branch: the 2x2 quad may straddle a quad and a triangle.
    vec2 w = max(fwidth(v_grid.xy), vec2(1e-8));
    float s = v_grid.x + v_grid.y;
    float ws = max(fwidth(s), 1e-8);
    vec2 d = abs(v_grid.xy - round(v_grid.xy)) / w;
    float e = min(d.x, d.y);
    if (mod(v_grid.z, 2.0) > 0.5) e = min(e, abs(s - round(s)) / ws);
    return e;
}

vec3 srgb_encode(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));
}

void main() {
    if (highlight.a > 0.0) {
        out_colour = highlight;
        return;
    }
    vec3 c;
    if (!gl_FrontFacing) {
        // The back of a two-sided surface's polygon is its twin's front, drawn there.
        if (v_grid.z > 1.5) discard;
        c = vec3(0.0); // the back of a polygon leaves no light
    } else if (flat_shading != 0) {
        uint leaf = triangle_leaf[primitive_base + uint(gl_PrimitiveID)];
        c = vec3(leaf_rgb[3u * leaf], leaf_rgb[3u * leaf + 1u], leaf_rgb[3u * leaf + 2u]);
    } else if (textured != 0) {
        c = emitted + texture(reflectance_map, v_st).rgb * v_colour;
    } else {
        c = v_colour;
    }
    if (patch_edges != 0) {
        // Dark lines about 1.5 pixels wide, with a one-pixel soft falloff.
        c *= mix(0.15, 1.0, smoothstep(0.5, 1.5, edge_distance_pixels()));
    }
    c *= scale;
    if (tone_map != 0) {
        // Extended Reinhard on luminance (as tone_map() in image.h), hue kept.
        float L = dot(c, vec3(0.2126, 0.7152, 0.0722));
        if (L > 0.0) {
            float Ld = L * (1.0 + L / (reinhard_white * reinhard_white)) / (1.0 + L);
            c *= Ld / L;
        }
        c = srgb_encode(c);
    }
    out_colour = vec4(c, 1.0);
}
