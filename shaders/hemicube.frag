#version 450 core
// Hemicube ID pass (paper 002 §2-§3): writes the receiving patch's ID and, in alpha, the
// analytic form factor from a differential area at the patch centre to the shooter.
//
//   R = float(index within level), G = float(level), B = float(polygon + 1) (0 = nothing,
//   -(polygon + 1) = the back of a polygon),
//   A = F(dA_j -> S) = 1/(2 pi) sum_k N_j . Gamma_k   (paper 002 eq. in §3.1)
//
// The mip level that GL selects from the patch-ID texture is the linking oracle: it picks the
// quadtree depth whose patches cover about one hemicube pixel.

layout(early_fragment_tests) in; // no depth writes or discards here: shade only the nearest

in vec2 v_param;
flat in int v_polygon;

layout(location = 0) out vec4 out_id;

struct PolygonData {
    vec4 v[4];      // corners in scene-local coordinates; v[3] unused for triangles
    vec4 normal;    // xyz: unit normal; w: 1 for a triangle, 0 for a quad
    ivec4 info;     // x: quadtree depth of the polygon
};
layout(std430, binding = 0) readonly buffer Polygons { PolygonData polygons[]; };
layout(std430, binding = 1) readonly buffer AcosTable { float acos_table[]; };

layout(binding = 0) uniform usampler2D patch_ids; // texel (x,y) of mip m: (x, y, depth, 0)

layout(location = 2) uniform vec3 shooter[4];      // shooter corners, scene-local
layout(location = 6) uniform int shooter_count;    // 3 or 4
layout(location = 7) uniform float lod_bias;
layout(location = 8) uniform int angle_method; // 0: lookup table, 1: GLSL acos, 2: GLSL atan
layout(location = 9) uniform int shooter_polygon;
layout(location = 10) uniform int polygons_only; // 1: B alone (a view probe), no texture lookup

const float PI = 3.14159265358979;

// The angle between unit vectors a and b (paper 002 §3.1: an arccos lookup table).
// The table holds acos(1 - s^2) at s = i/2047, uniform in s = sqrt(1 - x) with x = cos(angle),
// so entries crowd near x = 1 (small angles: far or small shooters), where acos is steepest.
// The index s is taken from the chord, sqrt(1 - a.b) = |a - b| / sqrt(2), rather than from
// a.b itself: near x = 1 a float dot product has lost the digits that the angle lives in
// (a 0.02 rad angle has 1 - x = 2e-4, known to 3e-4 relative in float).
float table_angle(vec3 a, vec3 b) {
    float x = dot(a, b);
    float s = (x >= 0.0 ? length(a - b) : length(a + b)) * 0.70710678;
    float t = min(s, 1.0) * float(acos_table.length() - 1);
    int i = min(int(t), acos_table.length() - 2);
    float angle = mix(acos_table[i], acos_table[i + 1], t - float(i));
    return x >= 0.0 ? angle : PI - angle;
}

float angle_between(vec3 a, vec3 b) {
    if (angle_method == 1) return acos(clamp(dot(a, b), -1.0, 1.0));
    if (angle_method == 2) return atan(length(cross(a, b)), dot(a, b));
    return table_angle(a, b);
}

// F(dA -> shooter polygon) at point p with unit normal n, the shooter clipped to the
// half-space n.(x - p) >= 0 first (the contour formula holds only above the tangent plane).
float point_to_shooter(vec3 p, vec3 n) {
    vec3 clipped[5];
    int count = 0;
    for (int k = 0; k < shooter_count; ++k) {
        vec3 a = shooter[k] - p;
        vec3 b = shooter[(k + 1) % shooter_count] - p;
        float da = dot(a, n), db = dot(b, n);
        if (da >= 0.0) clipped[count++] = a;
        if ((da >= 0.0) != (db >= 0.0)) {
            float t = da / (da - db);
            clipped[count++] = mix(a, b, t);
        }
    }
    if (count < 3) return 0.0;
    float sum = 0.0;
    for (int k = 0; k < count; ++k) {
        vec3 a = clipped[k];
        vec3 b = clipped[(k + 1) % count];
        float la = length(a), lb = length(b);
        if (la <= 0.0 || lb <= 0.0) continue;
        vec3 c = cross(a, b);
        float lc = length(c);
        if (lc <= 0.0) continue;
        sum += angle_between(a / la, b / lb) * dot(n, c / lc);
    }
    return clamp(abs(sum) / (2.0 * PI), 0.0, 1.0);
}

void main() {
    if (!gl_FrontFacing || v_polygon == shooter_polygon) {
        // An occluder seen from behind: blocks, receives nothing. B = -(polygon + 1) marks
        // it, so that a shooter whose centre is enclosed (under a block, behind a light) can
        // be detected, and the occluder's distance known.
        out_id = vec4(0.0, 0.0, -float(v_polygon + 1), 0.0);
        return;
    }
    if (polygons_only != 0) {
        out_id = vec4(0.0, 0.0, float(v_polygon + 1), 0.0);
        return;
    }
    PolygonData poly = polygons[v_polygon];
    bool triangle = poly.normal.w > 0.5;
    int max_level = poly.info.x;
    // The linking oracle: the depth encoded in the mip level GL picks for this fragment.
    uvec4 texel = texture(patch_ids, v_param, lod_bias);
    int level = min(int(texel.z), max_level);
    int n = 1 << level;
    vec2 uv = clamp(v_param, 0.0, 1.0);
    int index;
    vec2 centre;
    if (!triangle) {
        ivec2 cell = min(ivec2(uv * float(n)), ivec2(n - 1));
        index = cell.y * n + cell.x;
        centre = (vec2(cell) + 0.5) / float(n);
    } else {
        // Cell plus half of the cell: upright (lower-left) or inverted sub-triangle.
        ivec2 cell = min(ivec2(uv * float(n)), ivec2(n - 1));
        if (cell.x + cell.y > n - 1) {
            if (cell.x > 0) cell.x -= 1; else cell.y -= 1;
        }
        vec2 f = uv * float(n) - vec2(cell);
        bool inverted = f.x + f.y > 1.0 && cell.x + cell.y <= n - 2;
        if (inverted) {
            index = (n - 1 - cell.y) * n + (n - 1 - cell.x);
            centre = (vec2(cell) + 2.0 / 3.0) / float(n);
        } else {
            index = cell.y * n + cell.x;
            centre = (vec2(cell) + 1.0 / 3.0) / float(n);
        }
    }
    vec3 p;
    if (triangle) {
        p = poly.v[0].xyz + centre.x * (poly.v[1].xyz - poly.v[0].xyz) +
            centre.y * (poly.v[2].xyz - poly.v[0].xyz);
    } else {
        p = mix(mix(poly.v[0].xyz, poly.v[1].xyz, centre.x),
                mix(poly.v[3].xyz, poly.v[2].xyz, centre.x), centre.y);
    }
    float ff = point_to_shooter(p, poly.normal.xyz);
    out_id = vec4(float(index), float(level), float(v_polygon + 1), ff);
}
