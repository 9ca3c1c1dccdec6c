// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/bake/MpiJob.hpp"

#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>

#if URBANPVS_HAVE_MPI
// The C API only: the deprecated C++ bindings would need libmpi_cxx.
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#endif

namespace urbanpvs::preprocess {
namespace {

// The ranks the launcher announces: OpenMPI's mpirun, MPICH's Hydra and Slurm's PMI2, PMIx
// (srun --mpi=pmix). 0 when the process was not started as a rank of a job.
int launcher_size() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"})
    if (const char* v = std::getenv(name)) return std::atoi(v);
  if (std::getenv("PMIX_RANK")) return 2;  // PMIx without a size: start MPI and ask it
  return 0;
}

}  // namespace

#if URBANPVS_HAVE_MPI

MpiJob::MpiJob(int* argc, char*** argv) {
  if (launcher_size() <= 0) return;
  int provided = 0;
  MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
  started_ = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiJob::~MpiJob() {
  if (started_) MPI_Finalize();
}

void MpiJob::abort(int code) const {
  if (distributed()) MPI_Abort(MPI_COMM_WORLD, code);
}

std::vector<unsigned char> MpiJob::broadcast(std::vector<unsigned char> bytes) const {
  if (!distributed()) return bytes;
  unsigned long long n = bytes.size();
  MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
  bytes.resize(n);
  MPI_Bcast(bytes.data(), static_cast<int>(n), MPI_UNSIGNED_CHAR, 0, MPI_COMM_WORLD);
  return bytes;
}

void MpiJob::send(int to, int tag, std::span<const unsigned char> bytes) const {
  if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw std::length_error("MPI message over 2 GiB");
  MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_UNSIGNED_CHAR, to, tag,
           MPI_COMM_WORLD);
}

namespace {
MpiJob::Message receive_matching(int source) {
  MPI_Status status;
  MPI_Probe(source, MPI_ANY_TAG, MPI_COMM_WORLD, &status);
  int n = 0;
  MPI_Get_count(&status, MPI_UNSIGNED_CHAR, &n);
  MpiJob::Message m;
  m.from = status.MPI_SOURCE;
  m.tag = status.MPI_TAG;
  m.bytes.resize(static_cast<std::size_t>(n));
  MPI_Recv(m.bytes.data(), n, MPI_UNSIGNED_CHAR, m.from, m.tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return m;
}
}  // namespace

MpiJob::Message MpiJob::receive() const {
  return receive_matching(MPI_ANY_SOURCE);
}

MpiJob::Message MpiJob::receive_from(int from) const {
  return receive_matching(from);
}

bool MpiJob::message_waiting() const {
  int flag = 0;
  MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, MPI_STATUS_IGNORE);
  return flag != 0;
}

bool MpiJob::available() {
  return true;
}

#else  // a build without MPI: always a job of one

MpiJob::MpiJob(int*, char***) {
  if (const int n = launcher_size(); n > 1)
    throw std::runtime_error("started as one of " + std::to_string(n) +
                             " MPI ranks, but this build has no MPI (configure with "
                             "libopenmpi-dev installed and URBANPVS_MPI=ON); every rank would "
                             "bake the whole city alone");
}

MpiJob::~MpiJob() = default;

void MpiJob::abort(int) const {}

std::vector<unsigned char> MpiJob::broadcast(std::vector<unsigned char> bytes) const {
  return bytes;
}

void MpiJob::send(int, int, std::span<const unsigned char>) const {
  throw std::logic_error("MpiJob::send without MPI");
}

MpiJob::Message MpiJob::receive() const {
  throw std::logic_error("MpiJob::receive without MPI");
}

MpiJob::Message MpiJob::receive_from(int) const {
  throw std::logic_error("MpiJob::receive_from without MPI");
}

bool MpiJob::message_waiting() const {
  return false;
}

bool MpiJob::available() {
  return false;
}

#endif

const MpiJob& MpiJob::single() {
  static const MpiJob job;
  return job;
}

}  // namespace urbanpvs::preprocess
