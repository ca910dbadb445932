// hemirad: command-line front end. Errors are reported here, once: "hemirad: message" and a
// non-zero exit (2 for bad input, 1 for failures of the environment).
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>

#include "commands.h"
#include "hemirad/error.h"

namespace {

const char* kUsage =
    "usage: hemirad COMMAND [options]\n"
    "\n"
    "hemirad solves diffuse global illumination by progressive radiosity shooting, with form\n"
    "factors from a GPU hemicube (OpenGL 4.5, headless: EGL or OSMesa).\n"
    "\n"
    "commands:\n"
    "  solve SCENE        solve a scene; write reports, logs, probe values\n"
    "  scene SCENE        print what a scene holds (polygons, area, emitted power, warnings)\n"
    "  formfactors SCENE  form factors from one surface group to every group (paper 000)\n"
    "  reference SCENE    unbiased Monte-Carlo irradiance at probe points (the yardstick)\n"
    "  info               print the GL backend, vendor, renderer and version\n"
    "\n"
    "SCENE is an OBJ file, a glTF 2.0 file (.gltf, .glb), a SCENE.json project (OBJ or\n"
    "glTF files, IES and point luminaires,\n"
    "cameras; see README, \"Lighting design\") or a built-in scene: cornell, cube, furnace,\n"
    "sphere, room, cie53, cie56, cie57, cie58, room402, scene3138 (the files in assets/ hold\n"
    "them too).\n"
    "Run 'hemirad COMMAND --help' for a command's options.\n";

} // namespace

int main(int argc, char** argv) {
    if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h") ||
        !std::strcmp(argv[1], "help")) {
        std::fputs(kUsage, argc < 2 ? stderr : stdout);
        return argc < 2 ? 2 : 0;
    }
    const std::string command = argv[1];
    try {
        if (command == "info") return hemirad::cli::cmd_info(argc, argv);
        if (command == "scene") return hemirad::cli::cmd_scene(argc, argv);
        if (command == "solve") return hemirad::cli::cmd_solve(argc, argv);
        if (command == "formfactors") return hemirad::cli::cmd_formfactors(argc, argv);
        if (command == "reference") return hemirad::cli::cmd_reference(argc, argv);
        std::fprintf(stderr, "hemirad: unknown command '%s' (see hemirad --help)\n",
                     command.c_str());
        return 2;
    } catch (const hemirad::InputError& e) {
        std::fprintf(stderr, "hemirad: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "hemirad: %s\n", e.what());
        return 1;
    }
}
