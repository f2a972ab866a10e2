#pragma once
// How many threads `--threads 0` means: the cores this process may run on, as a batch scheduler or
// `taskset` set them, not every core of the machine.
namespace sedwave::app {

/// OMP_NUM_THREADS when it is set to a positive count (its first entry, as OpenMP reads a list);
/// else the CPUs in this process's affinity mask (sched_getaffinity); else
/// std::thread::hardware_concurrency(); at least 1.
[[nodiscard]] int usable_cores();

}  // namespace sedwave::app
