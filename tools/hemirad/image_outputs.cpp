#include "image_outputs.h"

#include "hemirad/error.h"

namespace hemirad::cli {

void add_image_options(ArgParser& args, ImageOutputOptions& o) {
    args.multi("-o", &o.files, "FILE", "write a view of the solution: .exr (linear) or .png");
}

void validate_image_options(const ImageOutputOptions& o) {
    if (!o.files.empty()) throw InputError("-o: image output is not implemented yet");
}

bool image_outputs_need_gl(const ImageOutputOptions& o) { return !o.files.empty(); }

void write_image_outputs(const ImageOutputOptions&, Solver&, bool) {}

} // namespace hemirad::cli
