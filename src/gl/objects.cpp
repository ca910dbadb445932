#include "gl/objects.h"

#include <cstdio>
#include <string>

#include "hemirad/error.h"

namespace hemirad::gl {

namespace {

const char* framebuffer_status_name(GLenum status) {
    switch (status) {
    case GL_FRAMEBUFFER_UNDEFINED:
        return "GL_FRAMEBUFFER_UNDEFINED";
    case GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT:
        return "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT";
    case GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT:
        return "GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT";
    case GL_FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER:
        return "GL_FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER";
    case GL_FRAMEBUFFER_INCOMPLETE_READ_BUFFER:
        return "GL_FRAMEBUFFER_INCOMPLETE_READ_BUFFER";
    case GL_FRAMEBUFFER_UNSUPPORTED:
        return "GL_FRAMEBUFFER_UNSUPPORTED";
    case GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE:
        return "GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE";
    case GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS:
        return "GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS";
    default:
        return "unknown status";
    }
}

} // namespace

Buffer Buffer::create() {
    GLuint id = 0;
    glCreateBuffers(1, &id);
    return Buffer(id);
}
void Buffer::destroy(GLuint id) noexcept {
    glDeleteBuffers(1, &id);
}
void Buffer::storage(GLsizeiptr size, const void* data, GLbitfield flags) {
    glNamedBufferStorage(id(), size, data, flags);
}

Texture Texture::create(GLenum target) {
    GLuint id = 0;
    glCreateTextures(target, 1, &id);
    return Texture(id, target);
}
void Texture::destroy(GLuint id) noexcept {
    glDeleteTextures(1, &id);
}
void Texture::storage_2d(GLsizei levels, GLenum internal_format, GLsizei width, GLsizei height) {
    glTextureStorage2D(id(), levels, internal_format, width, height);
}

Renderbuffer Renderbuffer::create() {
    GLuint id = 0;
    glCreateRenderbuffers(1, &id);
    return Renderbuffer(id);
}
void Renderbuffer::destroy(GLuint id) noexcept {
    glDeleteRenderbuffers(1, &id);
}
void Renderbuffer::storage(GLenum internal_format, GLsizei width, GLsizei height) {
    glNamedRenderbufferStorage(id(), internal_format, width, height);
}

FloatTarget FloatTarget::create(int width, int height) {
    while (glGetError() != GL_NO_ERROR) {} // earlier errors are not this allocation's
    FloatTarget t;
    t.width = width;
    t.height = height;
    t.colour = Texture::create(GL_TEXTURE_2D);
    t.colour.storage_2d(1, GL_RGBA32F, width, height);
    t.depth = Renderbuffer::create();
    t.depth.storage(GL_DEPTH_COMPONENT32F, width, height);
    if (glGetError() == GL_OUT_OF_MEMORY)
        throw InputError("the GL driver could not allocate a " + std::to_string(width) + " x " +
                         std::to_string(height) + " float framebuffer (" +
                         std::to_string(long(20.0 * width * height / (1 << 20))) + " MiB)");
    t.fbo = Framebuffer::create();
    t.fbo.attach(GL_COLOR_ATTACHMENT0, t.colour);
    t.fbo.attach(GL_DEPTH_ATTACHMENT, t.depth);
    t.fbo.check_complete();
    return t;
}

Framebuffer Framebuffer::create() {
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    return Framebuffer(id);
}
void Framebuffer::destroy(GLuint id) noexcept {
    glDeleteFramebuffers(1, &id);
}
void Framebuffer::attach(GLenum attachment, const Texture& texture, GLint level) {
    glNamedFramebufferTexture(id(), attachment, texture.id(), level);
}
void Framebuffer::attach(GLenum attachment, const Renderbuffer& renderbuffer) {
    glNamedFramebufferRenderbuffer(id(), attachment, GL_RENDERBUFFER, renderbuffer.id());
}
void Framebuffer::check_complete() const {
    const GLenum status = glCheckNamedFramebufferStatus(id(), GL_DRAW_FRAMEBUFFER);
    if (status == GL_FRAMEBUFFER_COMPLETE) return;
    char code[16];
    std::snprintf(code, sizeof code, "0x%04X", status);
    throw RuntimeError("framebuffer " + std::to_string(id()) +
                       " is incomplete: " + framebuffer_status_name(status) + " (" + code + ")");
}

VertexArray VertexArray::create() {
    GLuint id = 0;
    glCreateVertexArrays(1, &id);
    return VertexArray(id);
}
void VertexArray::destroy(GLuint id) noexcept {
    glDeleteVertexArrays(1, &id);
}
void VertexArray::vertex_buffer(GLuint binding, const Buffer& buffer, GLintptr offset,
                                GLsizei stride) {
    glVertexArrayVertexBuffer(id(), binding, buffer.id(), offset, stride);
}
void VertexArray::attribute(GLuint location, GLuint binding, GLint components, GLenum type,
                            GLuint offset) {
    glEnableVertexArrayAttrib(id(), location);
    glVertexArrayAttribFormat(id(), location, components, type, GL_FALSE, offset);
    glVertexArrayAttribBinding(id(), location, binding);
}

Shader Shader::create(GLenum stage) {
    return Shader(glCreateShader(stage));
}
void Shader::destroy(GLuint id) noexcept {
    glDeleteShader(id);
}

Program Program::create() {
    return Program(glCreateProgram());
}
void Program::destroy(GLuint id) noexcept {
    glDeleteProgram(id);
}

} // namespace hemirad::gl
