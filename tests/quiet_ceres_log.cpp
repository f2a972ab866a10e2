// Ceres logs through glog a line for every failed evaluation of a local fit, even with its own
// logging silent (a model evaluated outside a table's range, a profile step into a region the
// model does not cover). The fits check and report every failure themselves; the `sedwave`
// command silences glog the same way, so a passing test log holds no alarming lines.
#include <glog/logging.h>

namespace {
const bool kQuiet = [] {
  FLAGS_minloglevel = google::GLOG_FATAL;
  return true;
}();
}  // namespace
