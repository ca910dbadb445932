// Fuzz target: the glTF 2.0 loader (src/scene/gltf_loader.cpp, TinyGLTF underneath). The input
// is a whole file: binary glTF (.glb) when it starts with the magic "glTF", else JSON (.gltf,
// its buffers and images as data URIs). Bad input must end in an InputError; anything else
// (a crash, a sanitizer report, another exception) is a finding.
#include <string>

#include "fuzz_util.h"
#include "hemirad/error.h"
#include "hemirad/scene_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace hemirad;
    const std::string_view all = fuzz::as_view(data, size);
    const bool binary = all.substr(0, 4) == "glTF";
    const std::string path = fuzz::write_scratch(binary ? "scene.glb" : "scene.gltf", all);
    try {
        const Scene scene = load_gltf(path);
        (void)scene.content_hash();
    } catch (const InputError&) {}
    return 0;
}
