#pragma once
// Shared helpers of the DEM tests: MPI start-up for GoogleTest and small scene builders.
#include <gtest/gtest.h>
#include <mpi.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include "sedwave/forward/dem/engine.hpp"

namespace sedwave::forward::dem::testing {

/// Initialises MPI once for a GoogleTest binary (serial tests run on MPI_COMM_SELF).
class MpiEnvironment : public ::testing::Environment {
 public:
  void SetUp() override {
    int initialised = 0;
    MPI_Initialized(&initialised);
    if (!initialised) MPI_Init(nullptr, nullptr);
  }
  void TearDown() override {
    int finalised = 0;
    MPI_Finalized(&finalised);
    if (!finalised) MPI_Finalize();
  }
};

/// A file in the temporary directory whose name carries rank 0's process id of `comm`, so that
/// test binaries of several build trees (or ctest -j) running at once do not share files.
inline std::string temp_path(const std::string& name, MPI_Comm comm = MPI_COMM_SELF) {
  long pid = static_cast<long>(::getpid());
  MPI_Bcast(&pid, 1, MPI_LONG, 0, comm);
  return (std::filesystem::temp_directory_path() / ("sedwave_" + std::to_string(pid) + "_" + name)).string();
}

inline double sphere_mass(double density, double radius) {
  return density * 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
}

inline Grain make_grain(std::int64_t id, Vec3 position, double radius = 0.5, double density = 1.0) {
  Grain g;
  g.id = id;
  g.radius = radius;
  g.mass = sphere_mass(density, radius);
  g.position = position;
  return g;
}

/// Index of the local grain with global id `id` (throws if not local).
inline std::size_t local_index(const GrainArrays& g, std::int64_t id) {
  for (std::size_t i = 0; i < g.n_local(); ++i)
    if (g.id[i] == id) return i;
  throw std::out_of_range("grain not local");
}

/// An FCC crystal of n^3 cubic cells whose nearest neighbours overlap by `overlap` (diameter 1),
/// in a periodic box, with small random velocities of zero total momentum.
inline std::vector<Grain> compressed_fcc(int cells, double overlap, double speed, std::uint64_t seed,
                                         Box& box) {
  const double a = std::sqrt(2.0) * (1.0 - overlap);  // nearest distance a/sqrt(2) = 1 - overlap
  const Vec3 basis[4] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
  std::vector<Grain> grains;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, speed);
  Vec3 momentum;
  for (int ix = 0; ix < cells; ++ix)
    for (int iy = 0; iy < cells; ++iy)
      for (int iz = 0; iz < cells; ++iz)
        for (const Vec3& b : basis) {
          Grain g = make_grain(static_cast<std::int64_t>(grains.size()),
                               a * Vec3{ix + b.x + 0.25, iy + b.y + 0.25, iz + b.z + 0.25});
          g.velocity = {normal(rng), normal(rng), normal(rng)};
          momentum += g.mass * g.velocity;
          grains.push_back(g);
        }
  for (Grain& g : grains) g.velocity -= (1.0 / (g.mass * static_cast<double>(grains.size()))) * momentum;
  box.lo = {0, 0, 0};
  box.hi = a * Vec3{double(cells), double(cells), double(cells)};
  box.periodic = {true, true, true};
  return grains;
}

/// Runs on different rank counts differ only in the order of floating-point sums: positions and
/// velocities agree to this (grain diameters and diameters per time unit).
constexpr double kRankTolerance = 1e-9;

/// Largest difference in position (modulo the periodic directions) or velocity between two
/// snapshots keyed by grain id.
inline double max_difference(const std::map<std::int64_t, Grain>& a, const std::map<std::int64_t, Grain>& b,
                             const Box& box) {
  double worst = 0.0;
  for (const auto& [id, g] : a) {
    Vec3 d = g.position - b.at(id).position;
    for (int k = 0; k < 3; ++k)
      if (box.periodic[k]) d[k] -= box.length(k) * std::round(d[k] / box.length(k));
    worst = std::max({worst, norm(d), norm(g.velocity - b.at(id).velocity)});
  }
  return worst;
}

}  // namespace sedwave::forward::dem::testing
