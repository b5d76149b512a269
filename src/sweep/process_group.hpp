#pragma once
// The processes one sweep is spread over: MPI ranks when a binary runs under mpirun or srun
// (experiments/mpi_process_group.cpp), or threads standing in for them in tests. The sweeps
// (distributed_sweep.hpp) only exchange byte messages through this interface, so the library knows no MPI.
//
// Rank 0 is the root: it holds the journal, hands out runs, gathers every finished run and alone writes
// result files. The other ranks compute the runs they are handed and send them back.

#include <string>

namespace peg3d::sweep {

/// A message received from another rank.
struct GroupMessage {
  int from = 0;       ///< sender's rank
  std::string bytes;  ///< what it sent
};

class ProcessGroup {
 public:
  virtual ~ProcessGroup() = default;

  /// This process's rank in [0, size()).
  virtual int rank() const = 0;
  /// Processes in the group, >= 1.
  virtual int size() const = 0;
  bool is_root() const { return rank() == 0; }

  /// Sends `bytes` to rank `to` (!= rank()). Messages from one rank to another arrive in the order sent.
  virtual void send(int to, const std::string& bytes) = 0;
  /// Waits for the next message sent to this rank, from any rank. Waiting must leave the CPU to the threads
  /// computing runs (no busy spin).
  virtual GroupMessage receive() = 0;

  /// Collective, called once by every rank before the sweep starts: each passes 0 when its set-up succeeded,
  /// else the exit status it would end with (2 for an input error, 1 otherwise). Returns, on every rank, the
  /// lowest rank that failed and its status, or {-1, 0} when all succeeded.
  struct Failure {
    int rank = -1;
    int status = 0;
  };
  virtual Failure agree(int status) = 0;

  /// Ends every process of the group at once with `status`: the way out of a failure after the sweep started,
  /// when other ranks may wait on this one.
  [[noreturn]] virtual void abort(int status) = 0;
};

}  // namespace peg3d::sweep
