#pragma once
// MPI for the subcommands that need it (forward, table, dem): initialised when the command starts
// and finalised when it ends, so `sedwave invert` and `sedwave theory` never pay for it.
//
// How such a command fails on many ranks: a failure every rank throws alike is told once and ends
// every rank with the same status; any other may be on some ranks only, while the rest wait in a
// collective call (where MPI_Finalize would wait with them), so it ends the whole job.
#include <mpi.h>

#include <exception>
#include <functional>
#include <iosfwd>

namespace sedwave::app {

/// Thrown on the ranks that leave a failure to another rank to report: main prints nothing and
/// returns `status`.
struct QuietExit {
  int status;
};

/// Whether a launcher started this process as one of several ranks (from Open MPI's, MPICH's or
/// srun's environment variables), known before MPI starts.
[[nodiscard]] bool under_launcher();

/// Tells `failure` on `out` as a command's last words ("sedwave: error: ...", "sedwave: usage error:
/// ..."; nothing for QuietExit, nor for an agreed failure on any rank but its reporter) and returns
/// the command's exit status for it. `out` null: the status alone.
[[nodiscard]] int report_failure(const std::exception_ptr& failure, std::ostream* out);

class MpiSession {
 public:
  MpiSession();
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  [[nodiscard]] int rank() const { return rank_; }
  [[nodiscard]] int size() const { return size_; }

  /// Runs a command's body on every rank. A parallel::AgreedFailure thrown by every rank of the job
  /// is told once (by its reporter), and every rank then throws QuietExit with its exit status. Any
  /// other failure on more than one rank is told with this rank's number, and the job is aborted
  /// with kExitError.
  [[nodiscard]] int run(const std::function<int()>& body) const;

  /// Runs `work` (reading and checking the command's inputs, which every rank does alike) and agrees
  /// on its outcome (collective): where it fails on any rank, the lowest failing rank tells its
  /// failure (report_failure), and every rank throws QuietExit with that failure's exit status.
  void alike(const std::function<void()>& work) const;

  /// Rank 0 runs `tell` (a message every rank would print alike) while the others wait for it
  /// (collective): a rank that exits first makes the launcher end the one about to tell.
  void tell_once(const std::function<void()>& tell) const;

 private:
  bool owner_ = false;
  int rank_ = 0;
  int size_ = 1;
};

}  // namespace sedwave::app
