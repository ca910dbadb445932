// Fuzz target: the solution file reader (parse_solution, src/solver/solution_file.cpp) and
// the saved options (apply_solution_option). The first byte chooses the form: odd, the bytes
// are taken as they are (the checksum check is fuzzed); even, the rest is a file without its
// trailing checksum, which is appended, so that mutations reach the body's parser.
#include <string>

#include "fuzz_util.h"
#include "hemirad/error.h"
#include "hemirad/solution_file.h"

namespace {

std::uint64_t fnv1a(const std::string& b) {
    std::uint64_t h = 1469598103934665603ull;
    for (char c : b) h = (h ^ std::uint8_t(c)) * 1099511628211ull;
    return h;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace hemirad;
    if (size == 0) return 0;
    std::string bytes(fuzz::as_view(data + 1, size - 1));
    if (data[0] % 2 == 0) {
        const std::uint64_t h = fnv1a(bytes);
        for (int i = 0; i < 8; ++i) bytes.push_back(char((h >> (8 * i)) & 0xff));
    }
    try {
        const SolutionFile f = parse_solution(bytes, "fuzz.hrs");
        SolverOptions o;
        for (const SolutionOption& option : f.options) apply_solution_option(o, option, "fuzz.hrs");
        validate_options(o);
    } catch (const InputError&) {}
    return 0;
}
