// hemirad-bench experiment mpi_scaling (mpi_scaling.cpp).
#pragma once

namespace hemirad::bench {

/// The Cornell box to a 0.1 % bound with `hemirad solve` alone and under mpirun -np 1 and 2:
/// agreement with the single process (per surface group, against the two error bounds), and
/// what a round communicates (bytes, seconds). Prints its "JSON ..." and "ROW ..." lines.
void run_mpi_scaling();

} // namespace hemirad::bench
