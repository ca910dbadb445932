// Fuzz target: the scene assembly file (load_scene_json, src/scene/scene_json.cpp). The input
// is the JSON text; beside it in the scratch folder lie an OBJ of two quads, groups floor and
// window ("floor.obj", the window for "glazing"), and an IES file ("lamp.ies") that it may
// include, so that mutations reach the luminaire, glazing and camera parts as well as the key
// checks.
#include "fuzz_util.h"
#include "hemirad/error.h"
#include "hemirad/scene_io.h"

namespace {

constexpr const char* kObj = "v 0 0 0\nv 4 0 0\nv 4 0 4\nv 0 0 4\nv 0 2 0\nv 4 2 0\n"
                             "g floor\nf 4 3 2 1\ng window\nf 1 2 6 5\n";
constexpr const char* kIes =
    "IESNA:LM-63-2002\nTILT=NONE\n1 1000 1 3 1 1 2 0 0 0\n1 1 100\n0 45 90\n0\n"
    "100 70 0\n";

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace hemirad;
    static const bool files = [] {
        fuzz::write_scratch("floor.obj", kObj);
        fuzz::write_scratch("lamp.ies", kIes);
        return true;
    }();
    (void)files;
    const std::string path = fuzz::write_scratch("scene.json", fuzz::as_view(data, size));
    try {
        (void)load_scene_json(path);
    } catch (const InputError&) {}
    return 0;
}
