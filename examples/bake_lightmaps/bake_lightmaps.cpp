// Bakes lightmaps for an OBJ file: solves it, then writes per surface group an EXR atlas of
// radiosity and an OBJ with UVs into it (export.h).
//   bake_lightmaps SCENE.obj OUT_DIR [TOLERANCE]
#include <cstdio>
#include <exception>
#include <string>

#include <hemirad/hemirad.h>

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: bake_lightmaps SCENE.obj OUT_DIR [TOLERANCE]\n");
        return 2;
    }
    try {
        const hemirad::Scene scene = hemirad::load_obj(argv[1]);
        for (const std::string& w : scene.warnings)
            std::fprintf(stderr, "bake_lightmaps: warning: %s\n", w.c_str());
        hemirad::SolverOptions options;
        if (argc > 3) options.tolerance = std::stod(argv[3]);
        hemirad::Solver solver(scene, options);
        while (solver.step()) {}
        for (const std::string& file : hemirad::export_lightmaps(argv[2], solver.solution()))
            std::printf("%s\n", file.c_str());
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bake_lightmaps: %s\n", e.what());
        return 1;
    }
}
