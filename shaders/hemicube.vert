#version 450 core
// Hemicube ID pass: polygons as triangles with their patch parameters (u,v) and polygon id.

layout(location = 0) in vec3 position;   // scene-local: world minus the scene centre
layout(location = 1) in vec2 param;      // (u,v) on the polygon (include/hemirad/patch.h)
layout(location = 2) in float polygon;   // polygon index, exact as float below 2^24

layout(location = 0) uniform mat4 view_projection;
layout(location = 1) uniform vec3 eye;   // hemicube centre, scene-local

out vec2 v_param;
flat out int v_polygon;

void main() {
    v_param = param;
    v_polygon = int(polygon);
    gl_Position = view_projection * vec4(position - eye, 1.0);
}
