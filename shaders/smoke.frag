#version 450 core
// Smoke test (tests/gl_context_gl_test.cpp): the interpolated vertex colour, unclamped into a
// float colour buffer.

layout(location = 0) in vec4 v_color;

layout(location = 0) out vec4 frag_color;

void main() {
    frag_color = v_color;
}
