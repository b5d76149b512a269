#pragma once
// The MPI ranks of an experiment binary started by mpirun or srun, as the library's ProcessGroup. Built only
// when CMake finds MPI (PEG3D_HAVE_MPI); the experiment binaries join it through cli::sweep_main.

#include <memory>

#include "sweep/process_group.hpp"

namespace peg3d::cli {

/// Whether an MPI launcher started this process as one of several ranks (OpenMPI's mpirun, or a PMI/PMIx
/// launcher such as Slurm's srun --mpi=pmix). A program started by hand is alone and never initializes MPI.
bool launched_as_mpi_ranks();
/// How many ranks the launcher says it started (OMPI_COMM_WORLD_SIZE, PMI_SIZE); 0 when it does not say.
int launched_rank_count();

#ifdef PEG3D_HAVE_MPI
/// Initializes MPI (MPI_THREAD_SERIALIZED: on each rank one thread at a time talks to the others) on
/// MPI_COMM_WORLD; MPI_Finalize when destroyed. Throws std::runtime_error when MPI cannot give that thread
/// level.
std::unique_ptr<sweep::ProcessGroup> join_mpi_ranks(int* argc, char*** argv);
#endif

}  // namespace peg3d::cli
