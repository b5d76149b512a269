#include "mpi_process_group.hpp"

#include <cstdlib>
#include <string>

#ifdef PEG3D_HAVE_MPI
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <stdexcept>
#include <thread>

#include <fmt/format.h>
#endif

namespace peg3d::cli {

// OpenMPI's mpirun sets OMPI_COMM_WORLD_SIZE; PMIx (srun --mpi=pmix, prterun) PMIX_RANK; PMI-1/2 launchers
// (srun --mpi=pmi2, MPICH's hydra) PMI_SIZE.
bool launched_as_mpi_ranks() {
  for (const char* var : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE"}) {
    if (const char* v = std::getenv(var); v != nullptr && *v != '\0') return true;
  }
  return false;
}

int launched_rank_count() {
  for (const char* var : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"}) {
    if (const char* v = std::getenv(var); v != nullptr && *v != '\0') return std::atoi(v);
  }
  return 0;
}

#ifdef PEG3D_HAVE_MPI
namespace {

constexpr int kTag = 7;

void check(int status, const char* call) {
  if (status != MPI_SUCCESS) throw std::runtime_error(fmt::format("MPI: {} failed (error {})", call, status));
}

class MpiRanks final : public sweep::ProcessGroup {
 public:
  MpiRanks(int* argc, char*** argv) {
    int provided = 0;
    check(MPI_Init_thread(argc, argv, MPI_THREAD_SERIALIZED, &provided), "MPI_Init_thread");
    if (provided < MPI_THREAD_SERIALIZED) {
      MPI_Finalize();
      throw std::runtime_error("MPI: this MPI library cannot let worker threads talk to other ranks "
                               "(MPI_THREAD_SERIALIZED); run without mpirun, with --threads");
    }
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
  }
  ~MpiRanks() override { MPI_Finalize(); }

  int rank() const override { return rank_; }
  int size() const override { return size_; }

  void send(int to, const std::string& bytes) override {
    if (bytes.size() > static_cast<std::size_t>(INT_MAX)) {
      throw std::runtime_error(fmt::format("MPI: a message of {} bytes is too large to send", bytes.size()));
    }
    check(MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, to, kTag, MPI_COMM_WORLD), "MPI_Send");
  }

  // Polls with a growing pause instead of a blocking MPI_Recv, which spins at full speed in OpenMPI and would
  // take a core from the rank's worker threads. Answers come within a millisecond; runs last far longer.
  sweep::GroupMessage receive() override {
    MPI_Status status;
    auto pause = std::chrono::microseconds(20);
    for (int flag = 0;;) {
      check(MPI_Iprobe(MPI_ANY_SOURCE, kTag, MPI_COMM_WORLD, &flag, &status), "MPI_Iprobe");
      if (flag) break;
      std::this_thread::sleep_for(pause);
      pause = std::min(pause * 2, std::chrono::microseconds(1000));
    }
    int count = 0;
    MPI_Get_count(&status, MPI_BYTE, &count);
    sweep::GroupMessage m;
    m.from = status.MPI_SOURCE;
    m.bytes.resize(static_cast<std::size_t>(count));
    check(MPI_Recv(m.bytes.data(), count, MPI_BYTE, status.MPI_SOURCE, kTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
          "MPI_Recv");
    return m;
  }

  Failure agree(int status) override {
    // The lowest failing rank wins: min over (rank, status) packed in one int; INT_MAX for success.
    const int mine = status == 0 ? INT_MAX : rank_ * 256 + std::clamp(status, 1, 255);
    int lowest = INT_MAX;
    check(MPI_Allreduce(&mine, &lowest, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD), "MPI_Allreduce");
    if (lowest == INT_MAX) return {};
    return {lowest / 256, lowest % 256};
  }

  [[noreturn]] void abort(int status) override {
    MPI_Abort(MPI_COMM_WORLD, status);
    std::_Exit(status);  // MPI_Abort does not return; should it, end this rank anyway
  }

 private:
  int rank_ = 0;
  int size_ = 1;
};

}  // namespace

std::unique_ptr<sweep::ProcessGroup> join_mpi_ranks(int* argc, char*** argv) {
  return std::make_unique<MpiRanks>(argc, argv);
}
#endif

}  // namespace peg3d::cli
