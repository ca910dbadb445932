#version 450 core
// Solution view (src/render/solution_renderer.cpp): the leaf grid of every polygon, one vertex
// per grid corner. Smooth shading takes the vertex's colour from its welded node's average;
// flat shading ignores it and looks the leaf up per fragment.

layout(location = 0) in vec3 position; // scene-local: world minus the scene centre
layout(location = 1) in vec3 grid;     // (u n, v n) on the polygon's n x n leaf grid; z: 1 for a
                                       // triangle (lattice lines u+v = k too), 0 for a quad,
                                       // plus 2 for one side of a two-sided surface
layout(location = 2) in uint node;     // welded vertex (node) index
layout(location = 3) in vec2 st;       // texture coordinates (textured polygons)

layout(location = 0) uniform mat4 view_projection;
layout(location = 1) uniform int flat_shading; // 1: flat, 0: smooth

// Smooth values, RGB per node [W unit^-2], rewritten every frame.
layout(std430, binding = 2) readonly buffer NodeColours { float node_rgb[]; };

out vec3 v_colour;
out vec3 v_grid;
out vec2 v_st;

void main() {
    v_colour = flat_shading != 0 ? vec3(0.0)
                                 : vec3(node_rgb[3u * node], node_rgb[3u * node + 1u],
                                        node_rgb[3u * node + 2u]);
    v_grid = grid;
    v_st = st;
    gl_Position = view_projection * vec4(position, 1.0);
}
