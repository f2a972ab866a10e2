#include "mpi_session.hpp"

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

/// What alike() throws on the rank that reports the failure all ranks agreed on: run() passes the
/// exception inside on to main, as it was thrown.
struct ToReport {
  std::exception_ptr failure;
};

}  // namespace

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
  try {
    return body();
  } catch (const ToReport& agreed) {
    std::rethrow_exception(agreed.failure);
  } catch (const parallel::AgreedFailure& failure) {
    if (failure.ranks() == size_) throw;  // every rank of the job ends with it
    std::cerr << "sedwave: error on rank " << rank_ << ": " << failure.what() << '\n';
  } catch (const QuietExit&) {
    throw;
  } catch (const std::exception& failure) {
    if (size_ == 1) throw;
    std::cerr << "sedwave: error on rank " << rank_ << ": " << failure.what() << '\n';
  } catch (...) {
    if (size_ == 1) throw;
    std::cerr << "sedwave: error on rank " << rank_ << ": unknown exception\n";
  }
  std::cerr.flush();
  MPI_Abort(MPI_COMM_WORLD, kExitError);
  return kExitError;  // not reached: MPI_Abort ends every process of the job
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
  int status = failure ? report_failure(failure, nullptr) : kExitError;
  parallel::broadcast(MPI_COMM_WORLD, status, first);
  if (rank_ == first) throw ToReport{failure};
  throw QuietExit{status};
}

}  // namespace sedwave::app
