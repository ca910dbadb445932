#version 450 core
// Smoke test (tests/gl_context_gl_test.cpp): a triangle with a colour per vertex.

layout(location = 0) in vec2 position; // clip-space x, y
layout(location = 1) in vec4 color;

layout(location = 0) out vec4 v_color;

void main() {
    v_color = color;
    gl_Position = vec4(position, 0.0, 1.0);
}
