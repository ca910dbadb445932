// The EGL backend: a surfaceless display (EGL_MESA_platform_surfaceless: Mesa's llvmpipe on a
// machine without a GPU, or its default GPU), or one device of EGL_EXT_device_enumeration
// through EGL_EXT_platform_device. No surface: the context renders into framebuffer objects.
//
// Only glad's <glad/egl.h> here, never the system <EGL/egl.h>. libEGL is loaded by glad
// (gladLoaderLoadEGL) and stays loaded for the life of the process.
#include <cstdio>
#include <cstring>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include <glad/egl.h>

#include "gl/platform.h"
#include "hemirad/error.h"

namespace hemirad::gl::detail {

namespace {

// EGL_EXT_device_drm and EGL_EXT_device_drm_render_node: not in glad's extension list, and
// only read for device names.
constexpr EGLint kDrmDeviceFile = 0x3233;     // EGL_DRM_DEVICE_FILE_EXT
constexpr EGLint kDrmRenderNodeFile = 0x3377; // EGL_DRM_RENDER_NODE_FILE_EXT

const char* egl_error_name(EGLint error) {
    switch (error) {
    case EGL_SUCCESS:
        return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED:
        return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
        return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
        return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
        return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONTEXT:
        return "EGL_BAD_CONTEXT";
    case EGL_BAD_CONFIG:
        return "EGL_BAD_CONFIG";
    case EGL_BAD_CURRENT_SURFACE:
        return "EGL_BAD_CURRENT_SURFACE";
    case EGL_BAD_DISPLAY:
        return "EGL_BAD_DISPLAY";
    case EGL_BAD_SURFACE:
        return "EGL_BAD_SURFACE";
    case EGL_BAD_MATCH:
        return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
        return "EGL_BAD_PARAMETER";
    case EGL_BAD_NATIVE_PIXMAP:
        return "EGL_BAD_NATIVE_PIXMAP";
    case EGL_BAD_NATIVE_WINDOW:
        return "EGL_BAD_NATIVE_WINDOW";
    case EGL_CONTEXT_LOST:
        return "EGL_CONTEXT_LOST";
    default:
        return "unknown EGL error";
    }
}

/// Throws "<call> failed: EGL_BAD_MATCH (0x3009)" with the current EGL error.
[[noreturn]] void fail(const std::string& call) {
    const EGLint error = eglGetError();
    char code[16];
    std::snprintf(code, sizeof code, "0x%04X", static_cast<unsigned>(error));
    throw RuntimeError(call + " failed: " + egl_error_name(error) + " (" + code + ")");
}

bool has_extension(const char* list, const char* name) {
    const std::size_t n = std::strlen(name);
    for (const char* p = list ? std::strstr(list, name) : nullptr; p; p = std::strstr(p + n, name))
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
    return false;
}

/// Loads libEGL and the client entry points, the ones that need no display (platform
/// displays, device enumeration).
void load_egl_client() {
    if (gladLoaderLoadEGL(EGL_NO_DISPLAY) == 0)
        throw RuntimeError("could not load libEGL.so.1 (gladLoaderLoadEGL)");
}

std::vector<EGLDeviceEXT> query_devices() {
    if (!GLAD_EGL_EXT_device_enumeration) return {};
    EGLint count = 0;
    if (!eglQueryDevicesEXT(0, nullptr, &count)) fail("eglQueryDevicesEXT");
    std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
    if (!eglQueryDevicesEXT(count, devices.data(), &count)) fail("eglQueryDevicesEXT");
    devices.resize(static_cast<std::size_t>(count));
    return devices;
}

std::string device_name(EGLDeviceEXT device, std::size_t index) {
    const char* extensions =
        GLAD_EGL_EXT_device_query ? eglQueryDeviceStringEXT(device, EGL_EXTENSIONS) : nullptr;
    const char* file = nullptr;
    if (has_extension(extensions, "EGL_EXT_device_drm_render_node"))
        file = eglQueryDeviceStringEXT(device, kDrmRenderNodeFile);
    if (!file && has_extension(extensions, "EGL_EXT_device_drm"))
        file = eglQueryDeviceStringEXT(device, kDrmDeviceFile);
    if (file) return file;
    if (has_extension(extensions, "EGL_MESA_device_software")) return "software";
    return "device " + std::to_string(index);
}

EGLDisplay open_display(int device) {
    if (!GLAD_EGL_EXT_platform_base)
        throw RuntimeError("libEGL lacks the client extension EGL_EXT_platform_base "
                           "(no EGL driver installed?)");
    if (device < 0) {
        if (!GLAD_EGL_MESA_platform_surfaceless)
            throw RuntimeError("EGL lacks EGL_MESA_platform_surfaceless (not Mesa's libEGL?); "
                               "choose an EGL device instead");
        EGLDisplay display =
            eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (display == EGL_NO_DISPLAY)
            fail("eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA)");
        return display;
    }
    if (!GLAD_EGL_EXT_platform_device)
        throw RuntimeError("EGL lacks EGL_EXT_platform_device, needed to open a device");
    const std::vector<EGLDeviceEXT> devices = query_devices();
    if (static_cast<std::size_t>(device) >= devices.size())
        throw InputError("EGL device " + std::to_string(device) + " does not exist (" +
                         std::to_string(devices.size()) + " found)");
    EGLDisplay display =
        eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[device], nullptr);
    if (display == EGL_NO_DISPLAY)
        fail("eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, device " + std::to_string(device) +
             ")");
    return display;
}

class EglContext final : public Context {
  public:
    static std::unique_ptr<Context> create(const ContextOptions& options, bool debug);

    ~EglContext() override {
        if (context_ != EGL_NO_CONTEXT) {
            if (eglGetCurrentContext() == context_)
                eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            eglDestroyContext(display_, context_);
        }
        // The display is shared by every context on it (EGL gives one per native display):
        // the last context on it terminates it, and only then is the thread's state released
        // (another context may be current on it).
        if (initialised_ && release_display(display_)) {
            eglTerminate(display_);
            eglReleaseThread();
        }
    }

    std::string backend_name() const override { return "egl"; }

    void make_current() override {
        if (eglGetCurrentContext() == context_) return;
        if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
            fail("eglMakeCurrent");
    }

  private:
    explicit EglContext(EGLDisplay display) : display_(display) {}

    /// The contexts alive on each display: eglInitialize is counted, not nested, by EGL.
    static void hold_display(EGLDisplay display) {
        const std::lock_guard lock(displays_mutex_);
        ++displays_[display];
    }
    /// One context fewer on `display`; true if it was the last.
    static bool release_display(EGLDisplay display) {
        const std::lock_guard lock(displays_mutex_);
        return --displays_[display] == 0 && displays_.erase(display) > 0;
    }

    EGLDisplay display_;
    EGLContext context_ = EGL_NO_CONTEXT;
    bool initialised_ = false; ///< eglInitialize succeeded (hold_display counted it)
    static inline std::mutex displays_mutex_;
    static inline std::map<EGLDisplay, int> displays_;
};

std::unique_ptr<Context> EglContext::create(const ContextOptions& options, bool debug) {
    load_egl_client();
    EGLDisplay display = open_display(options.device);
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor)) fail("eglInitialize");
    // From here on the destructor cleans up whatever has been made.
    std::unique_ptr<EglContext> c(new EglContext(display));
    hold_display(display);
    c->initialised_ = true;

    // Again with the display: glad loads the display's version and extensions.
    if (gladLoaderLoadEGL(display) == 0)
        throw RuntimeError("gladLoaderLoadEGL with the display failed (EGL " +
                           std::to_string(major) + "." + std::to_string(minor) + ")");
    if (!GLAD_EGL_KHR_create_context)
        throw RuntimeError("the EGL display lacks EGL_KHR_create_context");
    if (!GLAD_EGL_KHR_surfaceless_context)
        throw RuntimeError("the EGL display lacks EGL_KHR_surfaceless_context");
    if (!eglBindAPI(EGL_OPENGL_API)) fail("eglBindAPI(EGL_OPENGL_API)");

    // No surface is ever made: any config that renders OpenGL will do.
    const EGLint config_attributes[] = {
        EGL_SURFACE_TYPE, 0,       EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_CONFORMANT,
        EGL_OPENGL_BIT,   EGL_NONE};
    EGLConfig config = nullptr;
    EGLint configs = 0;
    if (!eglChooseConfig(display, config_attributes, &config, 1, &configs)) fail("eglChooseConfig");
    if (configs == 0) throw RuntimeError("eglChooseConfig found no config for OpenGL");

    const EGLint context_attributes[] = {EGL_CONTEXT_MAJOR_VERSION_KHR,
                                         4,
                                         EGL_CONTEXT_MINOR_VERSION_KHR,
                                         5,
                                         EGL_CONTEXT_OPENGL_PROFILE_MASK_KHR,
                                         EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT_KHR,
                                         EGL_CONTEXT_FLAGS_KHR,
                                         debug ? EGL_CONTEXT_OPENGL_DEBUG_BIT_KHR : 0,
                                         EGL_NONE};
    c->context_ = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attributes);
    if (c->context_ == EGL_NO_CONTEXT) fail("eglCreateContext(OpenGL 4.5 core)");
    c->make_current();
    load_gl(reinterpret_cast<GLADloadfunc>(eglGetProcAddress), "eglGetProcAddress");
    return c;
}

} // namespace

std::unique_ptr<Context> create_egl_context(const ContextOptions& options, bool debug) {
    return EglContext::create(options, debug);
}

std::vector<std::string> egl_device_names() {
    try {
        load_egl_client();
        const std::vector<EGLDeviceEXT> devices = query_devices();
        std::vector<std::string> names;
        for (std::size_t i = 0; i < devices.size(); ++i)
            names.push_back(device_name(devices[i], i));
        return names;
    } catch (const RuntimeError&) {
        return {};
    }
}

} // namespace hemirad::gl::detail
