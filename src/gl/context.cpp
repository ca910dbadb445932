#include "hemirad/gl/context.h"

#include <string>

#include "gl/platform.h"
#include "hemirad/error.h"

namespace hemirad::gl {

namespace {

constexpr int kRequiredMajor = 4;
constexpr int kRequiredMinor = 5;

const char* backend_label(Backend backend) {
    switch (backend) {
    case Backend::Egl:
        return "EGL";
    case Backend::OSMesa:
        return "OSMesa";
    case Backend::Auto:
        break;
    }
    return "auto";
}

std::string gl_string(GLenum name) {
    const auto* s = reinterpret_cast<const char*>(glGetString(name));
    return s ? s : "";
}

} // namespace

// Creates one backend's context, then checks the version (a too-old context is a failure of
// that backend, so that Auto can fall back) and turns on debug output.
std::unique_ptr<Context> Context::create_backend(Backend backend, const ContextOptions& options) {
#ifdef HEMIRAD_GL_DEBUG
    const bool debug = true;
#else
    const bool debug = options.debug;
#endif
    std::unique_ptr<Context> context = backend == Backend::Egl
                                           ? detail::create_egl_context(options, debug)
                                           : detail::create_osmesa_context(options, debug);
    Context& c = *context;
    c.vendor_ = gl_string(GL_VENDOR);
    c.renderer_ = gl_string(GL_RENDERER);
    c.version_ = gl_string(GL_VERSION);
    glGetIntegerv(GL_MAJOR_VERSION, &c.major_);
    glGetIntegerv(GL_MINOR_VERSION, &c.minor_);
    GLint profile = 0;
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    const bool core = (profile & GL_CONTEXT_CORE_PROFILE_BIT) != 0;
    if (c.major_ * 10 + c.minor_ < kRequiredMajor * 10 + kRequiredMinor || !core)
        throw RuntimeError("got OpenGL " + std::to_string(c.major_) + "." +
                           std::to_string(c.minor_) + (core ? " core" : " (not core)") + " (\"" +
                           c.version_ + "\", " + c.renderer_ + "), hemirad needs " +
                           std::to_string(kRequiredMajor) + "." + std::to_string(kRequiredMinor) +
                           " core");
    if (debug) detail::enable_debug_output();
    return context;
}

std::unique_ptr<Context> Context::create(const ContextOptions& options) {
    static const char* const kInstall =
        ". Install libegl1 and libegl-mesa0 for EGL (on a GPU, the vendor's EGL driver), "
        "or libosmesa6 for OSMesa";
    if (options.backend != Backend::Auto) {
        try {
            return create_backend(options.backend, options);
        } catch (const RuntimeError& e) {
            throw RuntimeError(std::string("no OpenGL 4.5 core context from ") +
                               backend_label(options.backend) + ": " + e.what() + kInstall);
        }
    }
    std::string egl_reason;
    try {
        return create_backend(Backend::Egl, options);
    } catch (const RuntimeError& e) {
        egl_reason = e.what();
    }
    try {
        return create_backend(Backend::OSMesa, options);
    } catch (const RuntimeError& e) {
        throw RuntimeError("no OpenGL 4.5 core context: EGL: " + egl_reason +
                           "; OSMesa: " + e.what() + kInstall);
    }
}

Context::~Context() = default;

std::vector<std::string> Context::egl_devices() {
    return detail::egl_device_names();
}

Backend parse_backend(const std::string& name) {
    if (name == "auto") return Backend::Auto;
    if (name == "egl") return Backend::Egl;
    if (name == "osmesa") return Backend::OSMesa;
    throw InputError("unknown GL backend '" + name + "' (expected auto, egl or osmesa)");
}

namespace detail {

void load_gl(GLADloadfunc load, const char* backend) {
    if (gladLoadGL(load) == 0)
        throw RuntimeError(std::string("gladLoadGL with ") + backend +
                           " found no OpenGL entry points");
}

} // namespace detail

} // namespace hemirad::gl
