// Fuzz target: the OBJ/MTL loader (src/scene/obj_loader.cpp). The input is an OBJ file,
// optionally followed by a line "%%MTL" and the MTL library it may name as `mtllib m.mtl`.
// Bad input must end in an InputError; anything else (a crash, a sanitizer report, another
// exception) is a finding.
#include <cstdio>
#include <string>

#include "fuzz_util.h"
#include "hemirad/error.h"
#include "hemirad/scene_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace hemirad;
    const std::string_view all = fuzz::as_view(data, size);
    constexpr std::string_view kSplit = "\n%%MTL\n";
    const std::size_t split = all.find(kSplit);
    const std::string obj = fuzz::write_scratch("scene.obj", all.substr(0, split));
    const std::string mtl_path = fuzz::scratch_dir() + "/m.mtl";
    if (split != std::string_view::npos)
        fuzz::write_scratch("m.mtl", all.substr(split + kSplit.size()));
    else
        std::remove(mtl_path.c_str());
    try {
        const Scene scene = load_obj(obj);
        (void)scene.content_hash();
    } catch (const InputError&) {}
    return 0;
}
