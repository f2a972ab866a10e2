// The grid file of `sedwave table`: valid forms give the intended grid; every mistake is an error
// naming the file, the line and the key.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "sedwave/forward/table/grid_file.hpp"
#include "sedwave/forward/units.hpp"

namespace sedwave::forward::table {
namespace {

class GridFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("sedwave_grid_file_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_ / "scenes");
    std::ofstream(dir_ / "scenes" / "scene.toml") << "# a scene\n";
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  /// Writes `text` as grid.toml and reads it.
  TableGridFile read(const std::string& text) {
    std::ofstream(dir_ / "grid.toml") << text;
    return read_grid_file(dir_ / "grid.toml");
  }
  /// The error message reading `text` gives (empty if none).
  std::string error_of(const std::string& text) {
    try {
      (void)read(text);
    } catch (const GridFileError& e) {
      return e.what();
    }
    return "";
  }
  [[nodiscard]] std::string file() const { return (dir_ / "grid.toml").string(); }

  std::filesystem::path dir_;
};

TEST_F(GridFileTest, LogSpacedAndExplicitAxes) {
  const TableGridFile g = read(
      "scene = \"scenes/scene.toml\"\n"
      "omega_hat = { from = 0.01, to = 1, points = 3 }\n"
      "gamma_hat = [0.05, 0.2, 1]\n");
  EXPECT_EQ(g.scene_path, dir_ / "scenes" / "scene.toml");
  ASSERT_EQ(g.grid.omega_hat.size(), 3u);
  EXPECT_DOUBLE_EQ(g.grid.omega_hat[0], 0.01);
  EXPECT_NEAR(g.grid.omega_hat[1], 0.1, 1e-15);
  EXPECT_EQ(g.grid.omega_hat[2], 1.0);
  EXPECT_EQ(g.grid.gamma_hat, (std::vector<double>{0.05, 0.2, 1.0}));
  EXPECT_EQ(g.ranks_per_point, 1);
  EXPECT_TRUE(g.restitution.empty());
}

TEST_F(GridFileTest, RestitutionIsConvertedAndRecorded) {
  const TableGridFile g = read(
      "scene = \"scenes/scene.toml\"\n"
      "ranks_per_point = 2\n"
      "restitution = [0.9, 0.5]\n"
      "[omega_hat]\nfrom = 0.1\nto = 1.0\npoints = 2\n");
  ASSERT_EQ(g.grid.gamma_hat.size(), 2u);
  EXPECT_DOUBLE_EQ(g.grid.gamma_hat[0], gamma_hat_from_restitution(0.9));
  EXPECT_DOUBLE_EQ(g.grid.gamma_hat[1], gamma_hat_from_restitution(0.5));
  EXPECT_EQ(g.ranks_per_point, 2);
  EXPECT_NE(g.describe_axes().find("restitution e_n = [0.9, 0.5]"), std::string::npos) << g.describe_axes();
}

TEST_F(GridFileTest, ErrorsNameFileLineAndKey) {
  const std::string scene = "scene = \"scenes/scene.toml\"\n";
  const std::string omega = "omega_hat = [0.1, 1.0]\n";
  const std::string gamma = "gamma_hat = [0.1]\n";
  struct Case {
    std::string text;
    std::string expected;  // after "FILE:"
  };
  const Case cases[] = {
      {scene + omega + gamma + "ranks_per_pont = 2\n", "4: key 'ranks_per_pont': unknown key"},
      {scene + gamma + "[omega_hat]\nfrom = 0.1\nto = 1\npionts = 3\n", "6: key 'omega_hat.pionts': unknown key"},
      {scene + gamma + "[omega_hat]\nfrom = 0.1\nto = 1\n", "key 'omega_hat.points': missing"},
      {scene + "omega_hat = { from = 1.0, to = 0.1, points = 3 }\n" + gamma,
       "2: key 'omega_hat.to': must be greater than 'from'"},
      {scene + "omega_hat = [0.1, 1.0, 0.5]\n" + gamma, "2: key 'omega_hat[2]': must be strictly ascending"},
      {scene + omega + "gamma_hat = [0.1, -1]\n", "3: key 'gamma_hat[1]' = -1: accepted range (0, inf)"},
      {scene + omega + "gamma_hat = \"big\"\n", "3: key 'gamma_hat': must be a list"},
      {scene + omega + "restitution = [0.5, 0.9]\n", "3: key 'restitution[1]': must be strictly descending"},
      {scene + omega + "restitution = [1.0]\n", "3: key 'restitution[0]' = 1: accepted range (0, 1)"},
      {scene + omega + gamma + "restitution = [0.9]\n", "key 'gamma_hat': give exactly one"},
      {scene + omega + gamma + "ranks_per_point = 0\n", "4: key 'ranks_per_point' = 0: accepted range [1, 1000000] ranks"},
      {scene + omega + gamma + "ranks_per_point = 1.5\n", "4: key 'ranks_per_point': must be an integer"},
      {"scene = \"nowhere.toml\"\n" + omega + gamma, "1: key 'scene': no such file"},
      {omega + gamma, "key 'scene': missing"},
  };
  for (const Case& c : cases) {
    const std::string message = error_of(c.text);
    EXPECT_EQ(message.rfind(file() + ":", 0), 0u) << message;
    EXPECT_NE(message.find(c.expected), std::string::npos) << "expected '" << c.expected << "' in: " << message;
  }
}

TEST_F(GridFileTest, SyntaxErrorsNameFileAndLine) {
  const std::string message = error_of("scene = \"scenes/scene.toml\"\nomega_hat = [0.1,\n");
  EXPECT_EQ(message.rfind(file() + ":", 0), 0u) << message;
  EXPECT_NE(message.find("syntax error"), std::string::npos) << message;
  EXPECT_NE(message.find("2 | omega_hat = [0.1,"), std::string::npos) << message;
}

}  // namespace
}  // namespace sedwave::forward::table
