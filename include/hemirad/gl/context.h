// A headless OpenGL 4.5 core context (docs/design.md, "Headless GL"): EGL surfaceless (or an
// enumerated EGL device), with OSMesa as the fallback. One small platform class per backend
// behind this interface; no GL or EGL types here.
//
// GL entry points are process-wide (glad). Several contexts may live in one process (EGL's
// display is counted, the last context terminates it); whoever draws makes its own context
// current first (make_current() is cheap when it already is), as the hemicube provider does.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "hemirad/visibility.h"

namespace hemirad::gl {

enum class Backend {
    Auto,   ///< EGL, then OSMesa if EGL fails
    Egl,    ///< EGL: surfaceless platform, or an enumerated device (ContextOptions::device)
    OSMesa, ///< Mesa's off-screen renderer (software)
};

struct ContextOptions {
    Backend backend = Backend::Auto; ///< default Auto
    int device = -1;    ///< EGL device index (see Context::egl_devices()); -1: surfaceless default
    bool debug = false; ///< GL debug output to stderr; always on in HEMIRAD_GL_DEBUG builds
};

class HEMIRAD_API Context {
  public:
    /// Creates a GL >= 4.5 core context and makes it current on this thread. Throws
    /// hemirad::RuntimeError naming the call that failed (for Auto: both backends' reasons
    /// and what to install), or the GL version obtained when it is too low.
    static std::unique_ptr<Context> create(const ContextOptions& options = {});

    virtual ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    /// "egl" or "osmesa".
    virtual std::string backend_name() const = 0;
    /// Makes this context current on the calling thread.
    virtual void make_current() = 0;

    /// GL_VENDOR, GL_RENDERER, GL_VERSION as read when the context was created.
    std::string vendor() const { return vendor_; }
    std::string renderer() const { return renderer_; }
    std::string version() const { return version_; }
    int major_version() const { return major_; }
    int minor_version() const { return minor_; }

    /// Names of the EGL devices that EGL_EXT_device_enumeration lists, in index order (the
    /// index is ContextOptions::device): a DRM device file where EGL knows it, else
    /// "software" or "device <i>". Empty when EGL or the extension is missing.
    static std::vector<std::string> egl_devices();

  protected:
    Context() = default;

  private:
    static std::unique_ptr<Context> create_backend(Backend backend, const ContextOptions& options);

    std::string vendor_, renderer_, version_;
    int major_ = 0, minor_ = 0;
};

/// "auto", "egl" or "osmesa"; anything else throws hemirad::InputError naming the value.
HEMIRAD_API Backend parse_backend(const std::string& name);

} // namespace hemirad::gl
