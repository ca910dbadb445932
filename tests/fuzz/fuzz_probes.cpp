// Fuzz target: the probe CSV reader (read_probes, src/output/report.cpp), as given to
// `--probes` and `hemirad reference --probes`.
#include "fuzz_util.h"
#include "hemirad/error.h"
#include "hemirad/report.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace hemirad;
    const std::string path = fuzz::write_scratch("probes.csv", fuzz::as_view(data, size));
    try {
        (void)read_probes(path);
    } catch (const InputError&) {}
    return 0;
}
