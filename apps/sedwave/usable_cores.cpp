#include "usable_cores.hpp"

#include <sched.h>

#include <algorithm>
#include <cstdlib>
#include <string>
#include <thread>

namespace sedwave::app {
namespace {

/// OMP_NUM_THREADS's first entry ("4" or "4,2" for nested levels), or 0 when unset or not a count.
int omp_num_threads() {
  const char* text = std::getenv("OMP_NUM_THREADS");
  if (text == nullptr) return 0;
  const std::string value(text);
  const std::string first = value.substr(0, value.find(','));
  if (first.empty() || first.find_first_not_of("0123456789") != std::string::npos || first.size() > 6) return 0;
  return std::stoi(first);
}

int affinity_cpus() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof(set), &set) != 0) return 0;
  return CPU_COUNT(&set);
}

}  // namespace

int usable_cores() {
  if (const int requested = omp_num_threads(); requested > 0) return requested;
  if (const int cpus = affinity_cpus(); cpus > 0) return cpus;
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

}  // namespace sedwave::app
