#version 450 core
// Deliberately broken: tests/gl_context_gl_test.cpp checks that a compile error names this
// file. Do not fix, and do not use anywhere else.

layout(location = 0) out vec4 frag_color;

void main() {
    frag_color = vec4(1.0) +;
}
