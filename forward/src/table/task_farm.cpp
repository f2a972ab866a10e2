#include "sedwave/forward/table/task_farm.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <memory>
#include <optional>
#include <string_view>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "sedwave/forward/parallel/collectives.hpp"
#include "sedwave/forward/table/table_file.hpp"

namespace sedwave::forward::table {
namespace {

constexpr int kResultTag = 1;
/// How long an idle rank sleeps between polls. Open MPI's blocking calls busy-poll, which would steal
/// a core from ranks still computing when ranks outnumber cores; a point takes seconds to minutes, so
/// a few milliseconds of latency cost nothing.
constexpr auto kPollInterval = std::chrono::milliseconds(2);
constexpr int kProbeAttempts = 1000;

/// Waits for a non-blocking operation without spinning.
void wait_sleeping(MPI_Request& request) {
  int done = 0;
  for (MPI_Test(&request, &done, MPI_STATUS_IGNORE); !done; MPI_Test(&request, &done, MPI_STATUS_IGNORE)) {
    std::this_thread::sleep_for(kPollInterval);
  }
}

void barrier_sleeping(MPI_Comm comm) {
  MPI_Request request = MPI_REQUEST_NULL;
  MPI_Ibarrier(comm, &request);
  wait_sleeping(request);
}

// ---- A finished point on the wire ------------------------------------------------------------------

struct PointMessage {
  std::uint64_t todo_index = 0;  ///< position in the list of points to do
  std::int32_t group = 0;        ///< which group computed it (for the log)
  PointResult result;
};

/// Fixed-size numbers, then the reason's bytes: the whole message is one MPI_BYTE buffer.
struct WireHeader {
  std::uint64_t todo_index;
  std::int32_t group;
  std::int8_t status;
  double alpha_hat, c_hat, sigma_alpha_hat, sigma_c_hat, wall_seconds;
};

std::vector<char> pack(const PointMessage& m) {
  const WireHeader h{m.todo_index,         m.group,          static_cast<std::int8_t>(m.result.status),
                     m.result.alpha_hat,   m.result.c_hat,   m.result.sigma_alpha_hat,
                     m.result.sigma_c_hat, m.result.wall_seconds};
  std::vector<char> bytes(sizeof(WireHeader) + m.result.reason.size());
  std::memcpy(bytes.data(), &h, sizeof h);
  std::memcpy(bytes.data() + sizeof h, m.result.reason.data(), m.result.reason.size());
  return bytes;
}

PointMessage unpack(const std::vector<char>& bytes) {
  if (bytes.size() < sizeof(WireHeader)) throw std::runtime_error("task farm: truncated result message");
  WireHeader h{};
  std::memcpy(&h, bytes.data(), sizeof h);
  PointMessage m;
  m.todo_index = h.todo_index;
  m.group = h.group;
  m.result.status = static_cast<PointStatus>(h.status);
  m.result.alpha_hat = h.alpha_hat;
  m.result.c_hat = h.c_hat;
  m.result.sigma_alpha_hat = h.sigma_alpha_hat;
  m.result.sigma_c_hat = h.sigma_c_hat;
  m.result.wall_seconds = h.wall_seconds;
  m.result.reason.assign(bytes.data() + sizeof h, bytes.size() - sizeof h);
  return m;
}

// ---- Work distribution ------------------------------------------------------------------------------

/// A counter in rank 0's memory that every group leader increments atomically (MPI_Fetch_and_op
/// under a shared passive-target lock): the k-th call anywhere returns k. Rank 0 does not have to
/// take part: on one node Open MPI's shared-memory window does the atomic add in place.
class WorkCounter {
 public:
  explicit WorkCounter(MPI_Comm comm) : comm_(comm) {
    const MPI_Aint bytes = parallel::rank(comm) == 0 ? static_cast<MPI_Aint>(sizeof(std::int64_t)) : 0;
    MPI_Win_allocate(bytes, sizeof(std::int64_t), MPI_INFO_NULL, comm, &base_, &window_);
    if (parallel::rank(comm) == 0) {
      const std::int64_t zero = 0;
      MPI_Win_lock(MPI_LOCK_EXCLUSIVE, 0, 0, window_);
      MPI_Put(&zero, 1, MPI_INT64_T, 0, 0, 1, MPI_INT64_T, window_);
      MPI_Win_unlock(0, window_);
    }
    MPI_Barrier(comm);
  }
  WorkCounter(const WorkCounter&) = delete;
  WorkCounter& operator=(const WorkCounter&) = delete;
  ~WorkCounter() {
    barrier_sleeping(comm_);  // ranks that finished early wait here without spinning
    MPI_Win_free(&window_);
  }

  [[nodiscard]] std::int64_t next() {
    const std::int64_t one = 1;
    std::int64_t previous = 0;
    MPI_Win_lock(MPI_LOCK_SHARED, 0, 0, window_);
    MPI_Fetch_and_op(&one, &previous, MPI_INT64_T, 0, 0, MPI_SUM, window_);
    MPI_Win_unlock(0, window_);
    return previous;
  }

 private:
  MPI_Comm comm_;
  std::int64_t* base_ = nullptr;
  MPI_Win window_ = MPI_WIN_NULL;
};

/// Owns a communicator made for the farm.
class OwnedComm {
 public:
  explicit OwnedComm(MPI_Comm comm) : comm_(comm) {}
  OwnedComm(const OwnedComm&) = delete;
  OwnedComm& operator=(const OwnedComm&) = delete;
  ~OwnedComm() {
    if (comm_ != MPI_COMM_NULL) MPI_Comm_free(&comm_);
  }
  [[nodiscard]] MPI_Comm get() const { return comm_; }

 private:
  MPI_Comm comm_;
};

/// Rank 0's side: the table file, and what it has written.
class Writer {
 public:
  Writer(TableFile file, std::vector<GridIndex> todo, const FarmSettings& settings, FarmReport& report)
      : file_(std::move(file)), todo_(std::move(todo)), settings_(settings), report_(report) {}

  void write(const PointMessage& m) {
    const GridIndex index = todo_.at(m.todo_index);
    file_.write_point(index, m.result);
    ++written_;
    ++report_.computed;
    report_.point_seconds += m.result.wall_seconds;
    if (m.result.status == PointStatus::ok) ++report_.ok;
    else if (m.result.status == PointStatus::unresolved) ++report_.unresolved;
    else ++report_.failed;
    if (settings_.log) log(index, m);
  }

  /// Writes every result that has arrived; with `wait_for_all`, also waits (sleeping) for the rest.
  void receive(MPI_Comm farm, bool wait_for_all) {
    while (written_ < todo_.size()) {
      int arrived = 0;
      MPI_Status status;
      // One MPI_Iprobe may miss a message that has arrived: Open MPI pulls it out of the shared-memory
      // queue only during the probe's progress call (seen: results left waiting for a whole point).
      // A burst of probes costs microseconds.
      for (int attempt = 0; attempt < kProbeAttempts && !arrived; ++attempt) {
        MPI_Iprobe(MPI_ANY_SOURCE, kResultTag, farm, &arrived, &status);
      }
      if (!arrived) {
        if (!wait_for_all) return;
        std::this_thread::sleep_for(kPollInterval);
        continue;
      }
      int count = 0;
      MPI_Get_count(&status, MPI_BYTE, &count);
      std::vector<char> bytes(static_cast<std::size_t>(count));
      MPI_Recv(bytes.data(), count, MPI_BYTE, status.MPI_SOURCE, kResultTag, farm, MPI_STATUS_IGNORE);
      write(unpack(bytes));
    }
  }

 private:
  void log(GridIndex index, const PointMessage& m) const {
    const GridIndex& p = index;
    const TableGrid& grid = file_.table().grid();
    std::ostringstream line;
    line.precision(4);
    line << "[" << report_.already_finished + written_ << "/" << report_.points << "] omega_hat "
         << grid.omega_hat[p.i_omega] << " gamma_hat " << grid.gamma_hat[p.i_gamma] << ": "
         << to_string(m.result.status);
    if (m.result.status == PointStatus::ok) {
      line << " alpha_hat " << m.result.alpha_hat << " +- " << m.result.sigma_alpha_hat << " c_hat " << m.result.c_hat
           << " +- " << m.result.sigma_c_hat;
    } else {
      line << " (" << m.result.reason << ")";
    }
    line << " [" << m.result.wall_seconds << " s, group " << m.group << "]\n";
    *settings_.log << line.str() << std::flush;
  }

  TableFile file_;
  std::vector<GridIndex> todo_;
  const FarmSettings& settings_;
  FarmReport& report_;
  std::size_t written_ = 0;
};

/// Rank 0 opens (or resumes) the file; every rank learns the points to do, or rank 0's error.
std::vector<GridIndex> open_and_share_todo(MPI_Comm farm, const std::filesystem::path& table_path,
                                           const TableGrid& grid, const TableMetadata& metadata,
                                           const FarmSettings& settings, std::optional<TableFile>& file) {
  std::vector<std::uint64_t> flat;
  std::string error;
  if (parallel::rank(farm) == 0) {
    try {
      file.emplace(TableFile::resume_or_create(table_path, grid, metadata, settings.allow_changed_inputs));
      const DispersionTable& table = file->table();
      for (std::size_t g = 0; g < table.n_gamma(); ++g) {
        for (std::size_t w = 0; w < table.n_omega(); ++w) {
          const PointStatus status = table.at(g, w).status;
          if (status == PointStatus::missing || (settings.retry_failed && status == PointStatus::failed)) {
            flat.push_back(g * table.n_omega() + w);
          }
        }
      }
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  // Rank 0's failure must stop every rank, not leave them waiting in the next collective.
  parallel::throw_first_failure(farm, error);
  parallel::broadcast(farm, flat);
  std::vector<GridIndex> todo;
  for (std::uint64_t f : flat) todo.push_back({f / grid.omega_hat.size(), f % grid.omega_hat.size()});
  return todo;
}

PointResult compute_timed(const PointFunction& compute, MPI_Comm group, double omega_hat, double gamma_hat) {
  const auto start = std::chrono::steady_clock::now();
  PointResult result;
  try {
    result = compute(group, omega_hat, gamma_hat);
    if (result.status == PointStatus::missing) result = failed_point("the point function returned no result");
  } catch (const std::exception& e) {
    result = failed_point(e.what());
  }
  result.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace

FarmReport run_task_farm(MPI_Comm world, const std::filesystem::path& table_path, const TableGrid& grid,
                         const TableMetadata& metadata, const PointFunction& compute, const FarmSettings& settings) {
  const auto start = std::chrono::steady_clock::now();
  if (settings.ranks_per_point < 1 || parallel::size(world) % settings.ranks_per_point != 0) {
    throw std::invalid_argument("task farm: " + std::to_string(parallel::size(world)) + " ranks cannot form groups of " +
                                "ranks_per_point = " + std::to_string(settings.ranks_per_point) +
                                " (use a multiple of it with mpirun -np)");
  }
  grid.validate();
  // The farm's own messages travel on a private communicator, so they cannot meet the point
  // function's (which uses the group communicators).
  MPI_Comm farm_handle = MPI_COMM_NULL;
  MPI_Comm_dup(world, &farm_handle);
  const OwnedComm farm(farm_handle);
  const int rank = parallel::rank(farm.get());

  FarmReport report;
  report.points = grid.size();
  std::optional<TableFile> file;
  const std::vector<GridIndex> todo = open_and_share_todo(farm.get(), table_path, grid, metadata, settings, file);
  report.already_finished = grid.size() - todo.size();

  MPI_Comm group_handle = MPI_COMM_NULL;
  MPI_Comm_split(farm.get(), rank / settings.ranks_per_point, rank, &group_handle);
  const OwnedComm group(group_handle);
  const bool leader = parallel::rank(group.get()) == 0;
  const auto group_index = static_cast<std::int32_t>(rank / settings.ranks_per_point);

  std::optional<Writer> writer;
  if (rank == 0) writer.emplace(std::move(*file), todo, settings, report);
  {
    WorkCounter counter(farm.get());
    for (;;) {
      std::int64_t next = leader ? counter.next() : 0;
      parallel::broadcast(group.get(), next);
      if (next >= static_cast<std::int64_t>(todo.size())) break;
      const GridIndex p = todo[static_cast<std::size_t>(next)];
      const PointMessage m{static_cast<std::uint64_t>(next), group_index,
                           compute_timed(compute, group.get(), grid.omega_hat[p.i_omega], grid.gamma_hat[p.i_gamma])};
      if (rank == 0) {
        writer->write(m);
        writer->receive(farm.get(), false);  // what others finished meanwhile
      } else if (leader) {
        const std::vector<char> bytes = pack(m);
        MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, 0, kResultTag, farm.get());
      }
    }
    if (rank == 0) writer->receive(farm.get(), true);
  }  // ~WorkCounter: every rank waits here (sleeping) until rank 0 has written everything
  report.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

PointResult point_from_measurement(const std::string& problem, double alpha, double sigma_alpha, double c,
                                   double sigma_c, double wall_seconds) {
  if (!problem.empty()) return unresolved_point(problem, wall_seconds);
  const bool finite = std::isfinite(alpha) && std::isfinite(sigma_alpha) && std::isfinite(c) &&
                      std::isfinite(sigma_c) && c > 0.0;
  if (!finite) return unresolved_point("the propagation fit gave no finite alpha_hat and c_hat", wall_seconds);
  if (!(alpha >= 2.0 * sigma_alpha) || !(alpha > 0.0)) {
    std::ostringstream why;
    why.precision(3);
    why << "attenuation not significantly positive (alpha_hat " << alpha << " +- " << sigma_alpha
        << " < 2 sigma): the channel is too short to measure it";
    return unresolved_point(why.str(), wall_seconds);
  }
  PointResult p;
  p.status = PointStatus::ok;
  p.alpha_hat = alpha;
  p.c_hat = c;
  p.sigma_alpha_hat = sigma_alpha;
  p.sigma_c_hat = sigma_c;
  p.wall_seconds = wall_seconds;
  return p;
}

}  // namespace sedwave::forward::table
