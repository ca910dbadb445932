// Fuzz target: the parsers of option strings. The first byte picks the parser, the rest is
// its text:
//   0  --camera E,T,U,FOV (parse_camera, src/render/solution_renderer.cpp)
//   1  --grid GROUP:NXxNY (parse_grid_spec, src/solver/grid.cpp)
//   2  a command line (ArgParser, tools/common/cli/args.cpp, with hemirad solve's solver, scene and
//      --memory-limit options): the text split at NUL bytes into arguments (--help and -h
//      left out: they print the help and parse nothing)
//   3  --memory-limit SIZE (parse_memory_size, src/solver/memory_guard.cpp)
#include <string>
#include <vector>

#include "cli/cli_options.h"
#include "fuzz_util.h"
#include "hemirad/error.h"
#include "hemirad/grid.h"
#include "hemirad/memory_guard.h"
#include "hemirad/render.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace hemirad;
    if (size == 0) return 0;
    const std::string text(fuzz::as_view(data + 1, size - 1));
    try {
        switch (data[0] % 4) {
        case 0:
            (void)parse_camera(text);
            break;
        case 1:
            (void)parse_grid_spec(text);
            break;
        case 2: {
            std::vector<std::string> words{"hemirad-fuzz"};
            std::string w;
            for (char c : text) {
                if (c == '\0')
                    words.push_back(w), w.clear();
                else
                    w += c;
            }
            words.push_back(w);
            std::vector<char*> argv;
            for (std::string& s : words)
                if (s != "--help" && s != "-h") argv.push_back(s.data()); // prints, parses nothing
            ArgParser args("hemirad-fuzz", "hemirad-fuzz SCENE [options]", "fuzzing");
            std::string scene;
            args.positional("SCENE", &scene, "scene");
            SolverOptions so;
            BuiltinOptions bo;
            ObjOptions oo;
            add_solver_options(args, so);
            add_builtin_scene_options(args, bo);
            add_obj_scene_options(args, oo);
            std::vector<std::string> outputs;
            args.multi("-o", &outputs, "FILE", "output");
            if (args.parse(int(argv.size()), argv.data())) validate_options(so);
            break;
        }
        case 3:
            (void)parse_memory_size(text, "--memory-limit");
            break;
        }
    } catch (const InputError&) {}
    return 0;
}
