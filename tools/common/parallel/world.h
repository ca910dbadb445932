// The processes of this run. Launched by mpirun (Open MPI's or a PMI launcher's environment),
// a program built with MPI (HEMIRAD_MPI) starts MPI and takes part in it; started alone, or
// built without MPI, it is a world of one and makes no MPI call at all (no MPI runtime is
// needed then). main() builds the one World; parallel::world() returns it.
#pragma once

#include <string>

#include "hemirad/collective.h"

namespace hemirad::parallel {

class World final : public Collective {
  public:
    World(int& argc, char**& argv);
    World(); ///< a world of one that never starts MPI
    ~World() override;
    World(const World&) = delete;
    World& operator=(const World&) = delete;

    int rank() const override { return rank_; }
    int size() const override { return size_; }
    /// Rank among the processes on this machine (the default GPU / EGL device).
    int local_rank() const { return local_rank_; }
    /// Processes on this machine.
    int local_size() const { return local_size_; }
    std::vector<std::vector<std::uint8_t>>
    all_gather(const std::vector<std::uint8_t>& mine) override;
    bool any(bool flag) override;
    double last_transfer_seconds() const override { return transfer_seconds_; }
    /// Element-wise sum over the ranks, the same bits on every rank: summed on rank 0
    /// (MPI_Reduce), then broadcast. The dense alternative to all_gather's sparse lists
    /// (measured by hemirad-bench mpi_scaling, docs/scaling.md).
    void sum_to_all(std::vector<float>& values);
    /// Waits for every rank.
    void barrier();
    /// Ends every rank at once (MPI_Abort) with this exit status; a world of one just returns.
    void abort(int status);

    /// Built with MPI (HEMIRAD_MPI)?
    static bool built_with_mpi();
    /// Processes the launcher says it started (its environment), 1 when not launched by one.
    static int launched_size();

  private:
    int rank_ = 0, size_ = 1, local_rank_ = 0, local_size_ = 1;
    bool started_ = false; ///< this World called MPI_Init
    double transfer_seconds_ = 0;
};

/// The World main() built (a world of one when none was built, e.g. in the unit tests).
World& world();

} // namespace hemirad::parallel
