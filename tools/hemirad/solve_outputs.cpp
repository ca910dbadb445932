#include "solve_outputs.h"

#include <csignal>
#include <cstdio>

#include "hemirad/error.h"

namespace hemirad::cli {

namespace {
volatile std::sig_atomic_t g_interrupted = 0;
extern "C" void on_signal(int) {
    g_interrupted = 1;
}
} // namespace

void install_interrupt_handler() {
    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
}

bool interrupted() {
    return g_interrupted != 0;
}

void add_output_options(ArgParser& args, OutputOptions& o) {
    add_image_options(args, o.images);
}

void validate_output_options(const OutputOptions& o) {
    validate_image_options(o.images);
}

void write_outputs(const OutputOptions& o, Solver& solver, bool quiet) {
    write_image_outputs(o.images, solver, quiet);
}

void write_report(const std::string& path, Solver& solver, const Scene& scene,
                  const std::vector<GridResult>& grids, bool lux, double daylight_lux,
                  const Json* resume) {
    (void)scene;
    Json j = solve_report(solver, grids, lux, daylight_lux);
    if (resume) j["resume"] = *resume;
    write_text_file(path, j.dump() + "\n");
}

} // namespace hemirad::cli
