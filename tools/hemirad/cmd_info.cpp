// hemirad info: which OpenGL the engine would run on.
#include <cstdio>

#include "commands.h"
#include "hemirad/gl/context.h"

namespace hemirad::cli {

int cmd_info(int argc, char** argv) {
    std::string backend = "auto";
    int device = -1;
    bool list_devices = false;
    ArgParser args("hemirad info", "hemirad info [--backend auto|egl|osmesa] [--device N]",
                   "Creates a headless OpenGL 4.5 core context and prints what runs it.");
    args.option("--backend", &backend, "NAME", "auto (EGL, then OSMesa), egl or osmesa");
    args.option("--device", &device, "N", "EGL device index (-1 = the default display)");
    args.flag("--devices", &list_devices, "list the EGL devices and exit");
    if (!args.parse(argc, argv, 2)) return 0;
    if (list_devices) {
        const auto devices = gl::Context::egl_devices();
        for (std::size_t i = 0; i < devices.size(); ++i)
            std::printf("%zu  %s\n", i, devices[i].c_str());
        if (devices.empty()) std::printf("no EGL devices found\n");
        return 0;
    }
    gl::ContextOptions o;
    o.backend = gl::parse_backend(backend);
    o.device = device;
    const auto ctx = gl::Context::create(o);
    std::printf("backend   %s\n", ctx->backend_name().c_str());
    std::printf("vendor    %s\n", ctx->vendor().c_str());
    std::printf("renderer  %s\n", ctx->renderer().c_str());
    std::printf("version   %s\n", ctx->version().c_str());
    std::printf("gl        %d.%d core\n", ctx->major_version(), ctx->minor_version());
    return 0;
}

} // namespace hemirad::cli
