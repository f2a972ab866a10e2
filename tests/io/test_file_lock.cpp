// io::FileLock (io/include/sedwave/io/file_lock.hpp): a process finds the lock free and takes it at
// once; a second process waits for the holder, is told once that it waits, and takes the lock only
// after the holder let go; the lock file does not outlive its holder; a lock file that cannot be
// created is an error naming it.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "sedwave/io/file_lock.hpp"

namespace sedwave::io {
namespace {
namespace fs = std::filesystem;

fs::path fresh_directory() {
  const fs::path dir = fs::temp_directory_path() / ("sedwave-lock-" + std::to_string(::getpid()) + "-" +
                                                    ::testing::UnitTest::GetInstance()->current_test_info()->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(FileLock, IsTakenAtOnceWhenFreeAndLeavesNoFile) {
  const fs::path lock = fresh_directory() / "packing.h5.lock";
  int waits = 0;
  {
    const FileLock held(lock, [&] { ++waits; });
    EXPECT_EQ(waits, 0);
    EXPECT_TRUE(fs::exists(lock));
  }
  EXPECT_FALSE(fs::exists(lock));
}

TEST(FileLock, ASecondProcessWaitsUntilTheHolderLetsGo) {
  const fs::path dir = fresh_directory();
  const fs::path lock = dir / "packing.h5.lock", released = dir / "released";
  int held[2];
  ASSERT_EQ(::pipe(held), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    {
      const FileLock mine(lock);
      const char c = 'h';
      if (::write(held[1], &c, 1) != 1) ::_exit(2);
      ::usleep(300'000);
      std::ofstream(released) << "about to let go\n";
    }
    ::_exit(0);
  }
  char c = 0;
  ASSERT_EQ(::read(held[0], &c, 1), 1);  // the child holds the lock now
  int waits = 0;
  {
    const FileLock mine(lock, [&] { ++waits; });
    EXPECT_EQ(waits, 1) << "told once that it waits";
    EXPECT_TRUE(fs::exists(released)) << "taken while the other process still held it";
    EXPECT_TRUE(fs::exists(lock)) << "the holder's removed file was not replaced by a new one";
  }
  EXPECT_FALSE(fs::exists(lock));
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  ::close(held[0]);
  ::close(held[1]);
}

TEST(FileLock, NamesALockFileItCannotCreate) {
  const fs::path lock = fresh_directory() / "no-such-folder" / "packing.h5.lock";
  try {
    const FileLock held(lock);
    FAIL() << "locked " << lock;
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(lock.string()), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sedwave::io
