// Outputs that land safely (io/include/sedwave/io/atomic_file.hpp): symbolic links are written
// through, devices and FIFOs are written in place (text) or refused (HDF5), only a regular file is
// ever renamed over, temporaries are unique and the stale ones of dead processes are removed, a
// run's outputs land together or not at all, and one output directory has one writer.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <future>
#include <memory>
#include <sstream>
#include <string>

#include "sedwave/io/atomic_file.hpp"

namespace sedwave::io {
namespace {
namespace fs = std::filesystem;

class AtomicFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("sedwave-atomic-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path file(const std::string& name) const { return dir_ / name; }
  static std::string read(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }
  static void write(const fs::path& p, const std::string& text) {
    write_text_atomically(p, [&](std::ostream& out) { out << text; });
  }
  std::size_t entries() const {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()));
  }
  fs::path dir_;
};

TEST_F(AtomicFileTest, ReplacesARegularFileAndLeavesNoTemporary) {
  write(file("a.csv"), "old\n");
  write(file("a.csv"), "new\n");
  EXPECT_EQ(read(file("a.csv")), "new\n");
  EXPECT_EQ(entries(), 1u);
}

TEST_F(AtomicFileTest, WritesThroughASymbolicLinkAndKeepsTheLink) {
  write(file("target.csv"), "old\n");
  fs::create_symlink("target.csv", file("link.csv"));
  write(file("link.csv"), "new\n");
  EXPECT_TRUE(fs::is_symlink(file("link.csv")));
  EXPECT_EQ(read(file("target.csv")), "new\n");
}

TEST_F(AtomicFileTest, ADanglingLinkCreatesItsTarget) {
  fs::create_symlink("made.csv", file("link.csv"));
  write(file("link.csv"), "made\n");
  EXPECT_TRUE(fs::is_symlink(file("link.csv")));
  EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(file("made.csv"))));
  EXPECT_EQ(read(file("made.csv")), "made\n");
}

TEST_F(AtomicFileTest, AFifoIsWrittenInPlaceAndStaysAFifo) {
  ASSERT_EQ(::mkfifo(file("pipe").c_str(), 0600), 0);
  auto reader = std::async(std::launch::async, [&] { return read(file("pipe")); });
  write(file("pipe"), "through the pipe\n");
  EXPECT_EQ(reader.get(), "through the pipe\n");
  EXPECT_TRUE(fs::is_fifo(file("pipe")));
  EXPECT_EQ(entries(), 1u);
}

TEST_F(AtomicFileTest, DevNullIsWrittenInPlaceAndNeverReplaced) {
  write("/dev/null", "discarded\n");
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
}

TEST_F(AtomicFileTest, ALinkToAFifoIsWrittenInPlace) {
  ASSERT_EQ(::mkfifo(file("pipe").c_str(), 0600), 0);
  fs::create_symlink(file("pipe"), file("link"));
  auto reader = std::async(std::launch::async, [&] { return read(file("pipe")); });
  write(file("link"), "via the link\n");
  EXPECT_EQ(reader.get(), "via the link\n");
  EXPECT_TRUE(fs::is_symlink(file("link")));
  EXPECT_TRUE(fs::is_fifo(file("pipe")));
}

TEST_F(AtomicFileTest, SeekableOutputsRefuseAFifoAndADevice) {
  ASSERT_EQ(::mkfifo(file("pipe").c_str(), 0600), 0);
  for (const fs::path& target : {file("pipe"), fs::path("/dev/null")}) {
    try {
      write_seekable_atomically(target, [](std::ostream& out) { out << "x"; }, "HDF5");
      ADD_FAILURE() << "no error for " << target;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("HDF5 files must be seekable"), std::string::npos) << e.what();
    }
  }
  EXPECT_TRUE(fs::is_fifo(file("pipe")));
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  EXPECT_THROW(AtomicFile{file("pipe")}, std::invalid_argument);
}

TEST_F(AtomicFileTest, ADirectoryIsRefused) {
  fs::create_directories(file("sub"));
  EXPECT_THROW(write(file("sub"), "x"), std::invalid_argument);
  EXPECT_THROW(require_writable_location(file("sub"), "--out"), std::invalid_argument);
}

TEST_F(AtomicFileTest, TemporariesOfOneTargetAreDistinct) {
  AtomicFile a(file("t.csv")), b(file("t.csv"));
  EXPECT_NE(a.temporary(), b.temporary());
  EXPECT_TRUE(fs::exists(a.temporary()));
  EXPECT_TRUE(fs::exists(b.temporary()));
  const std::string name = a.temporary().filename().string();
  EXPECT_EQ(name.rfind("t.csv.tmp-", 0), 0u) << name;
}

TEST_F(AtomicFileTest, StaleTemporariesOfDeadProcessesAreRemovedOthersKept) {
  char host[256] = {};
  ASSERT_EQ(::gethostname(host, sizeof host - 1), 0);
  std::string this_host;
  for (const char* c = host; *c; ++c) this_host += std::isalnum(static_cast<unsigned char>(*c)) || *c == '.' ? *c : '_';
  // No process has a pid above the kernel's pid_max (at most 2^22).
  const std::string dead = std::to_string((1 << 22) + 7);
  const fs::path ours_dead = file("x.csv.tmp-" + this_host + "-" + dead + "-0123abcd");
  const fs::path old_form = file("x.csv.tmp-" + dead);
  const fs::path ours_alive = file("x.csv.tmp-" + this_host + "-1-0123abcd");  // pid 1 lives
  const fs::path foreign_fresh = file("x.csv.tmp-otherhost-" + dead + "-0123abcd");
  const fs::path not_ours = file("x.csv.tmp-notes.txt");
  for (const fs::path& p : {ours_dead, old_form, ours_alive, foreign_fresh, not_ours}) std::ofstream(p) << "x";
  write(file("x.csv"), "data\n");
  EXPECT_FALSE(fs::exists(ours_dead));
  EXPECT_FALSE(fs::exists(old_form));
  EXPECT_TRUE(fs::exists(ours_alive));
  EXPECT_TRUE(fs::exists(foreign_fresh));  // another host's write may still be running
  EXPECT_TRUE(fs::exists(not_ours));
  fs::last_write_time(foreign_fresh, fs::file_time_type::clock::now() - std::chrono::hours(25));
  write(file("x.csv"), "data\n");
  EXPECT_FALSE(fs::exists(foreign_fresh));
}

TEST_F(AtomicFileTest, DeferredCommitsLandTogetherOrNotAtAll) {
  write(file("a.csv"), "a0\n");
  write(file("b.csv"), "b0\n");
  {
    DeferredCommits run;
    write(file("a.csv"), "a1\n");
    EXPECT_EQ(read(file("a.csv")), "a0\n");  // not yet
    // The run fails before its second output: nothing of it lands.
  }
  EXPECT_EQ(read(file("a.csv")), "a0\n");
  EXPECT_EQ(read(file("b.csv")), "b0\n");
  EXPECT_EQ(entries(), 2u);
  {
    DeferredCommits run;
    write(file("a.csv"), "a2\n");
    write(file("b.csv"), "b2\n");
    run.commit_all();
    write(file("c.csv"), "c2\n");  // after commit_all: at once (a plot drawn from the files in place)
    EXPECT_EQ(read(file("c.csv")), "c2\n");
  }
  EXPECT_EQ(read(file("a.csv")), "a2\n");
  EXPECT_EQ(read(file("b.csv")), "b2\n");
  EXPECT_EQ(entries(), 3u);
}

TEST_F(AtomicFileTest, OneWriterPerOutputDirectory) {
  auto first = std::make_unique<OutputLock>(dir_, "--out");
  auto second = std::async(std::launch::async, [&] { return std::make_unique<OutputLock>(dir_, "--out"); });
  EXPECT_EQ(second.wait_for(std::chrono::milliseconds(300)), std::future_status::timeout);  // waits for the first
  first.reset();
  EXPECT_EQ(second.wait_for(std::chrono::seconds(10)), std::future_status::ready);
  EXPECT_NE(second.get(), nullptr);
}

}  // namespace
}  // namespace sedwave::io
