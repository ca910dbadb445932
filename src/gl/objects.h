// One move-only RAII type per GL object (docs/design.md, "GL objects"; after Magnum's GL/Buffer.h):
// copy deleted, move noexcept leaving the source empty (id 0), destructor deletes. A default-
// constructed object is empty and touches no GL; the factories (Buffer::create(), ...) make
// one with DSA and need a current context. The helpers are DSA too: nothing depends on what
// happens to be bound.
#pragma once

#include <utility>

#include <glad/gl.h>

namespace hemirad::gl {

namespace detail {

/// Owns one GL name. `Derived::destroy(GLuint)` deletes it.
template <class Derived> class Object {
  public:
    Object(const Object&) = delete;
    Object& operator=(const Object&) = delete;

    GLuint id() const noexcept { return id_; }
    explicit operator bool() const noexcept { return id_ != 0; }

  protected:
    Object() noexcept = default;
    explicit Object(GLuint id) noexcept : id_(id) {}
    Object(Object&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
    Object& operator=(Object&& other) noexcept {
        if (this != &other) {
            reset();
            id_ = std::exchange(other.id_, 0);
        }
        return *this;
    }
    ~Object() { reset(); }

  private:
    void reset() noexcept {
        if (id_ != 0) Derived::destroy(id_);
        id_ = 0;
    }

    GLuint id_ = 0;
};

} // namespace detail

class Buffer : public detail::Object<Buffer> {
  public:
    Buffer() noexcept = default;
    static Buffer create();

    /// Immutable storage of `size` bytes, from `data` (may be null); flags as for
    /// glNamedBufferStorage (0: written only by GL and by this call).
    void storage(GLsizeiptr size, const void* data, GLbitfield flags = 0);

  private:
    friend class detail::Object<Buffer>;
    explicit Buffer(GLuint id) noexcept : Object(id) {}
    static void destroy(GLuint id) noexcept;
};

class Texture : public detail::Object<Texture> {
  public:
    Texture() noexcept = default;
    static Texture create(GLenum target);

    GLenum target() const noexcept { return target_; }
    /// Immutable storage of a 2D (or 1D-array) texture: `levels` mip levels, the first one
    /// width x height [texels].
    void storage_2d(GLsizei levels, GLenum internal_format, GLsizei width, GLsizei height);

  private:
    friend class detail::Object<Texture>;
    Texture(GLuint id, GLenum target) noexcept : Object(id), target_(target) {}
    static void destroy(GLuint id) noexcept;

    GLenum target_ = 0;
};

class Renderbuffer : public detail::Object<Renderbuffer> {
  public:
    Renderbuffer() noexcept = default;
    static Renderbuffer create();

    /// width x height [pixels], single sample.
    void storage(GLenum internal_format, GLsizei width, GLsizei height);

  private:
    friend class detail::Object<Renderbuffer>;
    explicit Renderbuffer(GLuint id) noexcept : Object(id) {}
    static void destroy(GLuint id) noexcept;
};

class Framebuffer : public detail::Object<Framebuffer> {
  public:
    Framebuffer() noexcept = default;
    static Framebuffer create();

    void attach(GLenum attachment, const Texture& texture, GLint level = 0);
    void attach(GLenum attachment, const Renderbuffer& renderbuffer);
    /// Throws hemirad::RuntimeError naming the status (GL_FRAMEBUFFER_UNSUPPORTED, ...) when
    /// the framebuffer is not complete for drawing.
    void check_complete() const;

  private:
    friend class detail::Object<Framebuffer>;
    explicit Framebuffer(GLuint id) noexcept : Object(id) {}
    static void destroy(GLuint id) noexcept;
};

/// An offscreen target: an RGBA32F colour texture and a 32-bit float depth buffer of one
/// size, attached to a framebuffer (the hemicube's layouts, the solution renderer's views).
struct FloatTarget {
    int width = 0, height = 0;
    Texture colour;
    Renderbuffer depth;
    Framebuffer fbo;
    /// Throws hemirad::InputError naming the size when the driver is out of memory for it,
    /// hemirad::RuntimeError when the framebuffer is not complete.
    static FloatTarget create(int width, int height);
};

class VertexArray : public detail::Object<VertexArray> {
  public:
    VertexArray() noexcept = default;
    static VertexArray create();

    /// Binds `buffer` at binding point `binding`: vertices `stride` bytes apart from `offset`.
    void vertex_buffer(GLuint binding, const Buffer& buffer, GLintptr offset, GLsizei stride);
    /// Enables float attribute `location` (shader `layout(location = …)`): `components`
    /// values of `type` (converted to float, not normalised), `offset` bytes into each vertex
    /// of binding point `binding`.
    void attribute(GLuint location, GLuint binding, GLint components, GLenum type, GLuint offset);

  private:
    friend class detail::Object<VertexArray>;
    explicit VertexArray(GLuint id) noexcept : Object(id) {}
    static void destroy(GLuint id) noexcept;
};

class Shader : public detail::Object<Shader> {
  public:
    Shader() noexcept = default;
    /// stage: GL_VERTEX_SHADER, GL_FRAGMENT_SHADER, GL_COMPUTE_SHADER, ...
    static Shader create(GLenum stage);

  private:
    friend class detail::Object<Shader>;
    explicit Shader(GLuint id) noexcept : Object(id) {}
    static void destroy(GLuint id) noexcept;
};

class Program : public detail::Object<Program> {
  public:
    Program() noexcept = default;
    static Program create();

  private:
    friend class detail::Object<Program>;
    explicit Program(GLuint id) noexcept : Object(id) {}
    static void destroy(GLuint id) noexcept;
};

} // namespace hemirad::gl
