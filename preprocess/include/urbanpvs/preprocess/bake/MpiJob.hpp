// SPDX-License-Identifier: GPL-3.0-or-later
// The processes of one bake: the ranks of an MPI job when urbanpvs-preprocess was started by an
// MPI launcher (mpirun, mpiexec, srun), otherwise a job of one process. MPI is started only
// under a launcher, so a plain run never touches it (and a build without MPI still runs
// everywhere except as one of several ranks, which it refuses: every rank would bake alone).
// Only the thread that made the MpiJob calls MPI (MPI_THREAD_FUNNELED): worker threads compute
// cells and never communicate.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace urbanpvs::preprocess {

class MpiJob {
 public:
  /// Starts MPI when launched by an MPI launcher. Throws std::runtime_error when launched as
  /// one of several ranks by a build without MPI.
  MpiJob(int* argc, char*** argv);
  ~MpiJob();  ///< MPI_Finalize
  MpiJob(const MpiJob&) = delete;
  MpiJob& operator=(const MpiJob&) = delete;

  /// The job of one process that never starts MPI (library callers, tests).
  static const MpiJob& single();

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool distributed() const { return size_ > 1; }

  /// Ends every rank of the job with `code` (MPI_Abort): a failure on one rank must not leave
  /// the others waiting for it. Returns normally when the job is not distributed.
  void abort(int code) const;

  /// Rank 0's bytes on every rank (MPI_Bcast of a size, then the bytes).
  std::vector<unsigned char> broadcast(std::vector<unsigned char> bytes) const;
  /// Sends `bytes` to `to` with `tag` (blocking).
  void send(int to, int tag, std::span<const unsigned char> bytes) const;
  /// A message: its source, tag and bytes.
  struct Message {
    int from = 0;
    int tag = 0;
    std::vector<unsigned char> bytes;
  };
  /// Receives the next message from anyone (blocking).
  Message receive() const;
  /// Receives the next message from `from` (blocking).
  Message receive_from(int from) const;
  /// True when a message is waiting (MPI_Iprobe).
  bool message_waiting() const;

  /// Whether this build can run as several ranks.
  static bool available();

 private:
  MpiJob() = default;
  int rank_ = 0;
  int size_ = 1;
  bool started_ = false;  ///< this object called MPI_Init and must call MPI_Finalize
};

}  // namespace urbanpvs::preprocess
