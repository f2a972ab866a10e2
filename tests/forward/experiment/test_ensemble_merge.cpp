// Member tables of one ensemble merged into the ensemble's table (experiment/linear_points.hpp): the mean
// and standard error of the members, the table's significance rule applied to the mean, and clear
// refusals of tables that do not belong together. (That a merge reproduces a one-run ensemble
// table value for value is checked end to end in tests/forward/linear/cli_linear.sh.)
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "sedwave/forward/experiment/linear_points.hpp"

namespace sedwave::forward::experiment {
namespace {

using table::DispersionTable;
using table::PointResult;
using table::PointStatus;

DispersionTable member(int k, int n, std::vector<double> alpha, double c = 0.7) {
  table::TableMetadata m;
  m.scene_toml = "[geometry]\ngrains = 10\n";
  m.engine = member_engine_tag(k, n);
  DispersionTable t(table::TableGrid{{0.1, 0.2}, {1.0}}, m);
  for (std::size_t w = 0; w < 2; ++w) t.set(0, w, PointResult{PointStatus::ok, alpha[w], c + 0.01 * k, 1e-3, 1e-3, 1.0, {}});
  return t;
}

std::vector<std::string> names(std::size_t n) {
  std::vector<std::string> out;
  for (std::size_t k = 0; k < n; ++k) {
    std::string name = "m";  // built in steps: GCC 12 warns falsely (-Wrestrict) on "m" + s + ".h5"
    name += std::to_string(k);
    name += ".h5";
    out.push_back(name);
  }
  return out;
}

TEST(MergeMemberTables, MeanAndStandardErrorOfTheMembers) {
  // Point 0: 0.10 ... 0.14 -> mean 0.12, sd sqrt(0.001 / 4), se sd / sqrt(5). Point 1: one member's
  // attenuation is negative, yet the mean is significant: it counts, as in a one-run ensemble.
  std::vector<DispersionTable> tables;
  for (int k = 0; k < 5; ++k) tables.push_back(member(k, 5, {0.10 + 0.01 * k, k == 4 ? -0.001 : 0.05}));
  const DispersionTable merged = merge_member_tables(tables, names(5));
  EXPECT_EQ(merged.metadata().engine, "sedwave-linear");
  const double se = std::sqrt(0.001 / 4.0 / 5.0);
  const PointResult& p = merged.at(0, 0);
  ASSERT_EQ(p.status, PointStatus::ok);
  EXPECT_NEAR(p.alpha_hat, 0.12, 1e-15);
  EXPECT_NEAR(p.sigma_alpha_hat, se, 1e-15);
  EXPECT_NEAR(p.c_hat, 0.72, 1e-15);
  EXPECT_NEAR(p.sigma_c_hat, se, 1e-15);
  EXPECT_EQ(p.wall_seconds, 5.0);
  ASSERT_EQ(merged.at(0, 1).status, PointStatus::ok);
  EXPECT_NEAR(merged.at(0, 1).alpha_hat, 0.0398, 1e-15);
}

TEST(MergeMemberTables, InsignificantMeanAndUnresolvedMembersAreUnresolved) {
  std::vector<DispersionTable> tables{member(0, 2, {0.10, 0.01}), member(1, 2, {0.10, -0.01})};
  tables[1].set(0, 0, table::unresolved_point("the probes span less than one wavelength"));
  const DispersionTable merged = merge_member_tables(tables, names(2));
  EXPECT_EQ(merged.at(0, 0).status, PointStatus::unresolved);
  EXPECT_EQ(merged.at(0, 0).reason, "the probes span less than one wavelength");
  EXPECT_EQ(merged.at(0, 1).status, PointStatus::unresolved);  // mean 0 +- 0.01
  EXPECT_NE(merged.at(0, 1).reason.find("not significantly positive"), std::string::npos);
}

TEST(MergeMemberTables, OneMemberKeepsItsOwnErrors) {
  const std::vector<DispersionTable> tables{member(0, 1, {0.10, 0.05})};
  const DispersionTable merged = merge_member_tables(tables, names(1));
  EXPECT_EQ(merged.at(0, 0).sigma_alpha_hat, 1e-3);
}

TEST(MergeMemberTables, RefusesTablesThatDoNotBelongTogether) {
  auto refuses = [](std::vector<DispersionTable> tables, const std::string& why) {
    try {
      (void)merge_member_tables(tables, names(tables.size()));
      ADD_FAILURE() << "no error; expected: " << why;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
  };
  refuses({member(0, 2, {0.1, 0.1}), member(0, 2, {0.1, 0.1})}, "m1.h5 is member 0 again");
  refuses({member(0, 2, {0.1, 0.1}), member(1, 3, {0.1, 0.1})}, "m1.h5 belongs to an ensemble of 3");
  DispersionTable plain = member(1, 2, {0.1, 0.1});
  table::TableMetadata m = plain.metadata();
  m.engine = "sedwave-linear";
  refuses({member(0, 2, {0.1, 0.1}), DispersionTable(plain.grid(), m)}, "m1.h5 is not a member table");
  m.engine = member_engine_tag(1, 2);
  m.scene_toml = "[geometry]\ngrains = 20\n";
  refuses({member(0, 2, {0.1, 0.1}), DispersionTable(plain.grid(), m)}, "m1.h5 was computed from another scene");
  DispersionTable unfinished = member(1, 2, {0.1, 0.1});
  unfinished.set(0, 1, PointResult{});
  refuses({member(0, 2, {0.1, 0.1}), unfinished}, "m1.h5 has 1 points still missing");
}

}  // namespace
}  // namespace sedwave::forward::experiment
