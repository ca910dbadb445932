// hemirad: command-line front end. Errors are reported here, once: "hemirad: message" and a
// non-zero exit (2 for bad input, 1 for failures of the environment).
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>

#include <unistd.h>

#include "commands.h"
#include "hemirad/error.h"
#include "hemirad/version.h"
#include "parallel/world.h"

namespace {

const char* kUsage =
    "usage: hemirad COMMAND [options]\n"
    "       hemirad --version\n"
    "\n"
    "hemirad solves diffuse global illumination by progressive radiosity shooting, with form\n"
    "factors from a GPU hemicube (OpenGL 4.5, headless: EGL or OSMesa).\n"
    "\n"
    "commands:\n"
    "  solve SCENE        solve a scene; write reports, logs, probe values\n"
    "  batch SCENE...     solve many scenes, split across MPI ranks; a folder per scene\n"
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
    "Run 'hemirad COMMAND --help' for a command's options.\n"
    "\n"
    "Launched by 'mpirun -np N', solve shoots N shooters a round, one per rank, and batch\n"
    "splits its scenes across the ranks (docs/scaling.md).\n";

} // namespace

int main(int argc, char** argv) {
    if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h") ||
        !std::strcmp(argv[1], "help")) {
        std::fputs(kUsage, argc < 2 ? stderr : stdout);
        return argc < 2 ? 2 : 0;
    }
    if (!std::strcmp(argv[1], "--version")) {
        std::printf("hemirad %s\n", HEMIRAD_VERSION);
        return 0;
    }
    const std::string command = argv[1];
    // MPI starts here when mpirun launched this process (a world of one otherwise).
    hemirad::parallel::World world(argc, argv);
    // An error on one rank ends every rank (the others would wait in a collective forever);
    // rank 0 reports input errors (every rank finds the same), every rank its own failures.
    const auto fail = [&](const char* message, int status, bool every_rank) {
        if (world.size() == 1) {
            std::fprintf(stderr, "hemirad: %s\n", message);
            return status;
        }
        if (world.rank() == 0 || every_rank)
            std::fprintf(stderr, "hemirad: rank %d: %s\n", world.rank(), message);
        std::fflush(stderr);
        if (world.rank() != 0) usleep(500000); // let rank 0 print its message first
        world.abort(status);
        return status;
    };
    try {
        if (command == "info") return hemirad::cli::cmd_info(argc, argv);
        if (command == "scene") return hemirad::cli::cmd_scene(argc, argv);
        if (command == "solve") return hemirad::cli::cmd_solve(argc, argv);
        if (command == "batch") return hemirad::cli::cmd_batch(argc, argv);
        if (command == "formfactors") return hemirad::cli::cmd_formfactors(argc, argv);
        if (command == "reference") return hemirad::cli::cmd_reference(argc, argv);
        std::fprintf(stderr, "hemirad: unknown command '%s' (see hemirad --help)\n",
                     command.c_str());
        return 2;
    } catch (const hemirad::InputError& e) {
        return fail(e.what(), 2, false);
    } catch (const std::exception& e) {
        return fail(e.what(), 1, true);
    }
}
