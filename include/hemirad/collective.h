// What a solver running on several processes (MPI ranks) needs from them: who it is, how many
// they are, and two collectives. No MPI types here: tools/common/parallel/world.h implements it on
// MPI, so that the solver and the public headers never include <mpi.h>.
#pragma once

#include <cstdint>
#include <vector>

#include "hemirad/visibility.h"

namespace hemirad {

class HEMIRAD_API Collective {
  public:
    virtual ~Collective() = default;
    virtual int rank() const = 0; ///< 0 .. size()-1
    virtual int size() const = 0;
    /// Every rank's bytes, in rank order; every rank gets the same vectors.
    virtual std::vector<std::vector<std::uint8_t>>
    all_gather(const std::vector<std::uint8_t>& mine) = 0;
    /// True on every rank when `flag` is true on any rank.
    virtual bool any(bool flag) = 0;
    /// Of the last all_gather's time, the part spent moving the bytes once every rank had
    /// arrived (the rest was waiting for the slowest rank) [s].
    virtual double last_transfer_seconds() const { return 0; }
};

} // namespace hemirad
