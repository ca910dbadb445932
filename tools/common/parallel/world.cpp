// MPI behind parallel::World: MPI_Init only when a launcher started this process, an
// all-gather of byte vectors (sizes first, then MPI_Allgatherv) and a logical-or reduction.
#include "parallel/world.h"

#include <cstdlib>
#include <optional>
#include <string>

#include "core/parse.h"
#include "hemirad/error.h"

#if HEMIRAD_HAVE_MPI
// The C API only: Open MPI's deprecated C++ bindings would need their own library.
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#endif

namespace hemirad::parallel {

namespace {

World* g_world = nullptr;

int env_int(const char* name, int fallback) {
    const char* v = std::getenv(name);
    if (!v || !*v) return fallback;
    const std::optional<long long> n = parse_integer(v);
    return (n && *n >= 0 && *n < 1 << 24) ? int(*n) : fallback;
}

#if HEMIRAD_HAVE_MPI
void check(int rc, const char* what) {
    if (rc != MPI_SUCCESS) {
        char text[MPI_MAX_ERROR_STRING];
        int n = 0;
        MPI_Error_string(rc, text, &n);
        throw RuntimeError(std::string(what) + " failed: " + std::string(text, std::size_t(n)));
    }
}
#endif

} // namespace

int World::launched_size() {
    // Open MPI's mpirun, PMIx launchers (Slurm srun, prterun), PMI-1/2 (MPICH's hydra).
    for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_SIZE", "PMI_SIZE"}) {
        const int n = env_int(name, 0);
        if (n > 0) return n;
    }
    return std::getenv("PMIX_RANK") || std::getenv("PMI_RANK") ? 2 : 1;
}

bool World::built_with_mpi() {
    return HEMIRAD_HAVE_MPI != 0;
}

World::World() = default;

World::World(int& argc, char**& argv) {
    g_world = this;
#if HEMIRAD_HAVE_MPI
    const bool launched =
        std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMIX_RANK") || std::getenv("PMI_RANK");
    if (!launched) return;
    check(MPI_Init(&argc, &argv), "MPI_Init");
    started_ = true;
    // Errors come back as codes (check() throws) instead of ending the program unexplained.
    MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    MPI_Comm local;
    check(MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &local),
          "MPI_Comm_split_type");
    MPI_Comm_rank(local, &local_rank_);
    MPI_Comm_size(local, &local_size_);
    MPI_Comm_free(&local);
#else
    (void)argc;
    (void)argv;
#endif
}

World::~World() {
#if HEMIRAD_HAVE_MPI
    if (started_) MPI_Finalize();
#endif
    if (g_world == this) g_world = nullptr;
}

std::vector<std::vector<std::uint8_t>> World::all_gather(const std::vector<std::uint8_t>& mine) {
    if (size_ == 1) return {mine};
#if HEMIRAD_HAVE_MPI
    if (mine.size() > std::size_t(1) << 30)
        throw RuntimeError("MPI all-gather of " + std::to_string(mine.size()) +
                           " bytes from one rank: more than 1 GiB");
    int n = int(mine.size());
    const std::size_t n_ranks = static_cast<std::size_t>(size_);
    std::vector<int> sizes(n_ranks), offsets(n_ranks);
    // The sizes first: this all-gather also waits for the slowest rank; the second moves bytes.
    check(MPI_Allgather(&n, 1, MPI_INT, sizes.data(), 1, MPI_INT, MPI_COMM_WORLD), "MPI_Allgather");
    const double t0 = MPI_Wtime();
    long long total = 0;
    for (int r = 0; r < size_; ++r) {
        offsets[std::size_t(r)] = int(total);
        total += sizes[std::size_t(r)];
    }
    if (total > (1ll << 31) - 1)
        throw RuntimeError("MPI all-gather of " + std::to_string(total) +
                           " bytes: more than 2 GiB");
    std::vector<std::uint8_t> all(std::size_t(total) + 1);
    check(MPI_Allgatherv(mine.data(), n, MPI_BYTE, all.data(), sizes.data(), offsets.data(),
                         MPI_BYTE, MPI_COMM_WORLD),
          "MPI_Allgatherv");
    transfer_seconds_ = MPI_Wtime() - t0;
    std::vector<std::vector<std::uint8_t>> out(n_ranks);
    for (int r = 0; r < size_; ++r) {
        const std::uint8_t* p = all.data() + offsets[std::size_t(r)];
        out[std::size_t(r)].assign(p, p + sizes[std::size_t(r)]);
    }
    return out;
#else
    return {mine};
#endif
}

bool World::any(bool flag) {
    if (size_ == 1) return flag;
#if HEMIRAD_HAVE_MPI
    int in = flag ? 1 : 0, out = 0;
    check(MPI_Allreduce(&in, &out, 1, MPI_INT, MPI_LOR, MPI_COMM_WORLD), "MPI_Allreduce");
    return out != 0;
#else
    return flag;
#endif
}

void World::sum_to_all(std::vector<float>& values) {
    if (size_ == 1) return;
#if HEMIRAD_HAVE_MPI
    if (values.size() > std::size_t(1) << 30)
        throw RuntimeError("MPI sum of " + std::to_string(values.size()) + " floats: too many");
    const int n = int(values.size());
    std::vector<float> sum(values.size());
    check(MPI_Reduce(values.data(), sum.data(), n, MPI_FLOAT, MPI_SUM, 0, MPI_COMM_WORLD),
          "MPI_Reduce");
    if (rank_ == 0) values.swap(sum);
    check(MPI_Bcast(values.data(), n, MPI_FLOAT, 0, MPI_COMM_WORLD), "MPI_Bcast");
#endif
}

void World::barrier() {
#if HEMIRAD_HAVE_MPI
    if (size_ > 1) check(MPI_Barrier(MPI_COMM_WORLD), "MPI_Barrier");
#endif
}

void World::abort(int status) {
#if HEMIRAD_HAVE_MPI
    if (started_ && size_ > 1) MPI_Abort(MPI_COMM_WORLD, status);
#else
    (void)status;
#endif
}

World& world() {
    static World alone;
    return g_world ? *g_world : alone;
}

} // namespace hemirad::parallel
