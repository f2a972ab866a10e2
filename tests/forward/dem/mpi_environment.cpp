// MPI start-up for the serial DEM tests: they run on MPI_COMM_SELF inside one GoogleTest binary,
// which initialises MPI once before the first test and finalises it after the last.
#include "dem_test_support.hpp"

namespace {
const auto* const kMpi =
    ::testing::AddGlobalTestEnvironment(new sedwave::forward::dem::testing::MpiEnvironment);
}  // namespace
