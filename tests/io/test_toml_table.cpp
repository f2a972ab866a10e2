// The strict TOML reader's guards (io/toml_table.hpp): what toml11 itself would crash on, take
// quadratic time over, or misread, is refused or reported as written.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "sedwave/io/toml_table.hpp"

namespace sedwave::io {
namespace {

struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::string message_of(const std::string& text) {
  try {
    parse<Error>(text, "scene.toml");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

std::string nested(int depth) {
  const auto n = static_cast<std::size_t>(depth);
  return "x = " + std::string(n, '[') + "1" + std::string(n, ']') + "\n";
}

TEST(TomlShape, NestingIsBoundedBeforeParsing) {
  EXPECT_EQ(message_of(nested(kMaxTomlNesting)), "");
  EXPECT_EQ(message_of("a = 1\n" + nested(kMaxTomlNesting + 1)),
            "scene.toml:2: syntax error: arrays or inline tables nested deeper than 64 levels");
  // Brackets in strings and comments are not nesting.
  const std::string brackets(200, '[');
  EXPECT_EQ(message_of("a = \"" + brackets + "\" # " + brackets + "\nb = '" + brackets + "'\nc = \"\"\"\n" + brackets +
                       "\n\"\"\"\n"),
            "");
}

TEST(TomlShape, LongLinesAreRefusedAndLongArraysOverManyLinesAccepted) {
  std::string one_line = "x = [", many_lines = "x = [\n";
  for (int k = 0; k < 20000; ++k) {
    one_line += "0.25, ";
    many_lines += "0.25,\n";
  }
  EXPECT_EQ(message_of("a = 1\n" + one_line + "]\n").rfind("scene.toml:2: syntax error: a line longer than 65536", 0), 0u);
  EXPECT_EQ(message_of(many_lines + "]\n"), "");
}

TEST(TomlTable, IntegersBeyond64BitsAreReportedAsWritten) {
  const toml::value root = parse<Error>("n = 99999999999999999999\nm = 1_000\nx = 99999999999999999999\n", "scene.toml");
  Table<Error> t(root, "", "scene.toml");
  try {
    (void)t.integer<int>("n", 0, Range::closed(1, 1e5));
    FAIL() << "accepted";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "scene.toml:1: key 'n' = 99999999999999999999: accepted range [1, 100000]");
  }
  EXPECT_EQ(t.integer<int>("m", 0, Range::closed(1, 1e5)), 1000);  // underscores are no overflow
  try {
    (void)t.number("x", 0.0);
    FAIL() << "accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("99999999999999999999 does not fit a 64-bit integer"), std::string::npos);
  }
}

}  // namespace
}  // namespace sedwave::io
