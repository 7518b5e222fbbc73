// Sweeps on the ranks of an MPI job (docs/scale-out.md): rank 0 reads and validates the
// sweep, hands the points out from a queue (the most costly first), computes points itself on a
// thread of its own and is the only writer; the other ranks compute the points they are handed and
// send each piece back. Only the main thread of a rank calls MPI (MPI_THREAD_FUNNELED). Built with
// FOGRADAR_WITH_MPI; a build without it refuses a process that an MPI launcher started.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "fogradar/sweep/spec.hpp"
#include "fogradar/sweep/sweep.hpp"

namespace fogradar::sweep {

// This process's rank and the job's size as its launcher (mpirun, srun) puts them in the
// environment, read before MPI starts; nothing where no launcher started it (or gives no size).
std::optional<std::size_t> launched_rank();
std::optional<std::size_t> launched_size();
bool built_with_mpi();

// Rank 0 refused the input and has said why: every rank exits with status 2, and no other message.
class RefusedOnRankZero : public std::runtime_error {
 public:
  RefusedOnRankZero() : std::runtime_error("rank 0 refused the input") {}
};

// MPI for the object's life: MPI_Init_thread (MPI_THREAD_FUNNELED) and, when the object ends
// normally or with a refusal every rank agreed on, MPI_Finalize. A rank that ends with any other
// exception leaves MPI unfinished, and the launcher aborts the job (MPI's model; the points
// committed so far stay for --resume). Throws InvalidParameter naming "mpirun" when fogradar was
// built without MPI (RefusedOnRankZero on the other ranks).
class MpiJob {
 public:
  MpiJob();
  ~MpiJob();
  MpiJob(const MpiJob&) = delete;
  MpiJob& operator=(const MpiJob&) = delete;

  std::size_t rank() const { return rank_; }
  std::size_t size() const { return size_; }

  // Rank 0 runs `check`; a refusal there (InvalidParameter) is rethrown on rank 0 and becomes
  // RefusedOnRankZero on the others, so bad input is told once and every rank exits with 2.
  void settle(const std::function<void()>& check);
  // Rank 0's `text`, on every rank.
  std::string share(const std::string& text) const;

 private:
  std::size_t rank_ = 0;
  std::size_t size_ = 1;
  bool refused_ = false;
};

// run_sweep() on the ranks of `job`, every rank calling it with the same sweep: the outcome
// (tables, counts) on rank 0; the other ranks' outcomes count only the points they computed.
SweepOutcome run_sweep(MpiJob& job, const SweepSpec& spec, const std::vector<Point>& points,
                       const std::filesystem::path& dir, const SweepOptions& options);

}  // namespace fogradar::sweep
