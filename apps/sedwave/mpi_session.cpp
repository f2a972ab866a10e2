#include "mpi_session.hpp"

#include <cstdlib>
#include <exception>
#include <iostream>
#include <ostream>
#include <string>

#include "commands.hpp"
#include "output_paths.hpp"
#include "sedwave/forward/parallel/collectives.hpp"

namespace sedwave::app {
namespace {

namespace parallel = sedwave::forward::parallel;

/// Ends every rank with `status` once the failure they agreed on has been told: each rank waits here
/// until all have come, so that no rank exits (which makes the launcher kill the others) before the
/// one that tells it has written its message.
[[noreturn]] void end_together(int status) {
  std::cerr.flush();
  MPI_Barrier(MPI_COMM_WORLD);
  throw QuietExit{status};
}

}  // namespace

bool under_launcher() {
  // Slurm: the step's task count (srun), not the allocation's, which a batch script's own serial
  // commands see too.
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "SLURM_STEP_NUM_TASKS"}) {
    if (const char* value = std::getenv(name); value != nullptr && std::atoi(value) > 1) return true;
  }
  return false;
}

int report_failure(const std::exception_ptr& failure, std::ostream* out) {
  const auto tell = [out](const char* kind, const char* what) {
    if (out != nullptr) *out << "sedwave: " << kind << ": " << what << '\n';
  };
  try {
    std::rethrow_exception(failure);
  } catch (const UsageError& e) {
    tell("usage error", e.what());
    return kExitUsage;
  } catch (const QuietExit& quiet) {
    return quiet.status;  // another rank tells it
  } catch (const parallel::AgreedFailure& e) {
    if (e.reporter()) tell("error", e.what());  // one rank tells what all ranks agreed on
    return kExitError;
  } catch (const std::exception& e) {
    tell("error", e.what());
    return kExitError;
  } catch (...) {
    tell("error", "unknown exception");
    return kExitError;
  }
}

MpiSession::MpiSession() {
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (!initialised) {
    MPI_Init(nullptr, nullptr);
    owner_ = true;
  }
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiSession::~MpiSession() {
  if (owner_) MPI_Finalize();
}

int MpiSession::run(const std::function<int()>& body) const {
  // The line goes out in one write: std::cerr is unbuffered, and piece by piece it would interleave
  // with what Open MPI prints as it aborts the other ranks.
  const auto say = [this](const char* what) {
    std::cerr << "sedwave: error on rank " + std::to_string(rank_) + ": " + what + "\n";
  };
  try {
    return body();
  } catch (const parallel::AgreedFailure& failure) {
    if (failure.ranks() == size_) end_together(report_failure(std::current_exception(), &std::cerr));
    say(failure.what());
  } catch (const QuietExit&) {
    throw;
  } catch (const std::exception& failure) {
    if (size_ == 1) throw;
    say(failure.what());
  } catch (...) {
    if (size_ == 1) throw;
    say("unknown exception");
  }
  std::cerr.flush();
  MPI_Abort(MPI_COMM_WORLD, kExitError);
  return kExitError;  // not reached: MPI_Abort ends every process of the job
}

void MpiSession::tell_once(const std::function<void()>& tell) const {
  if (rank_ == 0) tell();
  std::cout.flush();
  std::cerr.flush();
  MPI_Barrier(MPI_COMM_WORLD);
}

void MpiSession::alike(const std::function<void()>& work) const {
  std::exception_ptr failure;
  try {
    work();
  } catch (...) {
    failure = std::current_exception();
  }
  if (size_ == 1) {
    if (failure) std::rethrow_exception(failure);
    return;
  }
  const int first = parallel::min(MPI_COMM_WORLD, failure ? rank_ : size_);
  if (first == size_) return;
  int status = rank_ == first ? report_failure(failure, &std::cerr) : kExitError;
  parallel::broadcast(MPI_COMM_WORLD, status, first);
  end_together(status);
}

}  // namespace sedwave::app
