// The OSMesa backend: Mesa's off-screen renderer (llvmpipe), the fallback when EGL is
// missing. It renders into framebuffer objects; the colour buffer OSMesa needs to make a
// context current is a small one that the context owns.
//
// <GL/osmesa.h> includes the system <GL/gl.h>, which clashes with glad: glad's <glad/gl.h>
// comes first (through platform.h) and sets gl.h's include guard, so osmesa.h only needs
// the GLAPI/GLAPIENTRY macros that gl.h would have defined.
#include "gl/platform.h"

#ifndef GLAPI
#define GLAPI extern
#endif
#ifndef GLAPIENTRY
#define GLAPIENTRY
#endif
#include <GL/osmesa.h>

#include <vector>

#include "hemirad/error.h"

namespace hemirad::gl::detail {

namespace {

class OSMesaBackedContext final : public Context {
  public:
    static std::unique_ptr<Context> create();

    ~OSMesaBackedContext() override {
        if (OSMesaGetCurrentContext() == context_) OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
        OSMesaDestroyContext(context_);
    }

    std::string backend_name() const override { return "osmesa"; }

    void make_current() override {
        if (OSMesaGetCurrentContext() == context_) return;
        if (!OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, kSize, kSize))
            throw RuntimeError("OSMesaMakeCurrent failed");
    }

  private:
    static constexpr int kSize = 16; ///< side of the unused default colour buffer [pixels]

    explicit OSMesaBackedContext(OSMesaContext context)
        : context_(context), buffer_(kSize * kSize * 4) {}

    OSMesaContext context_;
    std::vector<unsigned char> buffer_; ///< RGBA8, kSize x kSize
};

std::unique_ptr<Context> OSMesaBackedContext::create() {
    const int attributes[] = {OSMESA_FORMAT,
                              OSMESA_RGBA,
                              OSMESA_DEPTH_BITS,
                              0,
                              OSMESA_STENCIL_BITS,
                              0,
                              OSMESA_ACCUM_BITS,
                              0,
                              OSMESA_PROFILE,
                              OSMESA_CORE_PROFILE,
                              OSMESA_CONTEXT_MAJOR_VERSION,
                              4,
                              OSMESA_CONTEXT_MINOR_VERSION,
                              5,
                              0};
    OSMesaContext context = OSMesaCreateContextAttribs(attributes, nullptr);
    if (!context)
        throw RuntimeError("OSMesaCreateContextAttribs(RGBA, OpenGL 4.5 core) returned null");
    std::unique_ptr<OSMesaBackedContext> c(new OSMesaBackedContext(context));
    c->make_current();
    load_gl(reinterpret_cast<GLADloadfunc>(OSMesaGetProcAddress), "OSMesaGetProcAddress");
    return c;
}

} // namespace

// OSMesa has no debug-context attribute; Mesa gives debug output without one.
std::unique_ptr<Context> create_osmesa_context(const ContextOptions& options, bool debug) {
    return OSMesaBackedContext::create();
}

} // namespace hemirad::gl::detail
