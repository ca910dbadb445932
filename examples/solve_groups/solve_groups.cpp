// Solves a scene and prints the average irradiance of every surface group.
//   solve_groups [SCENE [TOLERANCE]]     SCENE: built-in name, OBJ or SCENE.json (cornell)
#include <cstdio>
#include <exception>
#include <string>

#include <hemirad/hemirad.h>

int main(int argc, char** argv) {
    try {
        const hemirad::Scene scene = hemirad::load_scene(argc > 1 ? argv[1] : "cornell");
        hemirad::SolverOptions options;
        if (argc > 2) options.tolerance = std::stod(argv[2]);
        hemirad::Solver solver(scene, options);
        while (solver.step()) {}
        const hemirad::Hierarchy& h = solver.solution();
        std::printf("# %s: %s after %ld shots, error bound %.3g\n", scene.source.c_str(),
                    hemirad::to_string(solver.stop_reason()), solver.shots(), solver.error_bound());
        std::printf("# group E_avg_r E_avg_g E_avg_b [W/unit^2]\n");
        for (std::uint32_t g = 0; g < scene.groups.size(); ++g) {
            const hemirad::GroupIrradiance e = hemirad::group_irradiance(h, g);
            std::printf("%s %.9g %.9g %.9g\n", scene.groups[g].c_str(), e.E_avg.x, e.E_avg.y,
                        e.E_avg.z);
        }
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "solve_groups: %s\n", e.what());
        return 1;
    }
}
