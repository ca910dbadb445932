// Fuzz target: the IES LM-63 reader (parse_ies, src/scene/ies_reader.cpp), as given to a
// SCENE.json luminaire's "ies".
#include "fuzz_util.h"
#include "hemirad/error.h"
#include "hemirad/photometry.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace hemirad;
    try {
        const IesFile ies = parse_ies(std::string(fuzz::as_view(data, size)), "fuzz.ies");
        (void)ies;
    } catch (const InputError&) {}
    return 0;
}
