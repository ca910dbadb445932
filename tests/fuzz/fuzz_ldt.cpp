// Fuzz target: the EULUMDAT reader (parse_eulumdat, src/scene/eulumdat_reader.cpp), as given to
// a SCENE.json luminaire's "ldt" (or "ies", told apart by content).
#include "fuzz_util.h"
#include "hemirad/error.h"
#include "hemirad/photometry.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace hemirad;
    try {
        const EulumdatFile ldt = parse_eulumdat(std::string(fuzz::as_view(data, size)), "fuzz.ldt");
        (void)ldt.distribution.lumens();
    } catch (const InputError&) {}
    return 0;
}
