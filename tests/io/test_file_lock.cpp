// io::FileLock (io/include/sedwave/io/file_lock.hpp): a process finds the lock free and takes it at
// once; a second process waits for the holder, is told once that it waits, and takes the lock only
// after the holder let go; a holder killed with SIGKILL leaves the lock free; a lock file that cannot
// be created is an error naming it.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
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

/// A child process that takes the lock, says so through a pipe, runs `then` and exits (status 3
/// if anything throws). Returns its pid once it holds the lock.
template <class Then>
pid_t child_holding(const fs::path& lock, Then then) {
  int held[2];
  if (::pipe(held) != 0) throw std::runtime_error("pipe");
  const pid_t child = ::fork();
  if (child < 0) throw std::runtime_error("fork");
  if (child == 0) {
    ::close(held[0]);
    try {
      const FileLock mine(lock);
      const char c = 'h';
      if (::write(held[1], &c, 1) != 1) ::_exit(2);
      then();
    } catch (...) {
      ::_exit(3);
    }
    ::_exit(0);
  }
  ::close(held[1]);  // so that a child dying before it writes makes read() return 0, not block
  char c = 0;
  const ssize_t n = ::read(held[0], &c, 1);
  ::close(held[0]);
  if (n != 1) throw std::runtime_error("the child never held the lock");
  return child;
}

int exit_status(pid_t child) {
  int status = 0;
  if (::waitpid(child, &status, 0) != child) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -2;
}

TEST(FileLock, IsTakenAtOnceWhenFree) {
  const fs::path lock = fresh_directory() / "packing.h5.lock";
  int waits = 0;
  {
    const FileLock held(lock, [&] { ++waits; });
    EXPECT_EQ(waits, 0);
    EXPECT_TRUE(fs::exists(lock));
  }
  const FileLock again(lock, [&] { ++waits; });  // released: free again
  EXPECT_EQ(waits, 0);
}

TEST(FileLock, ASecondProcessWaitsUntilTheHolderLetsGo) {
  const fs::path dir = fresh_directory();
  const fs::path lock = dir / "packing.h5.lock", released = dir / "released";
  const pid_t child = child_holding(lock, [&] {
    ::usleep(300'000);
    std::ofstream(released) << "about to let go\n";
  });
  int waits = 0;
  {
    const FileLock mine(lock, [&] { ++waits; });
    EXPECT_EQ(waits, 1) << "told once that it waits";
    EXPECT_TRUE(fs::exists(released)) << "taken while the other process still held it";
  }
  EXPECT_EQ(exit_status(child), 0);
}

TEST(FileLock, AKilledHolderLeavesItFree) {
  const fs::path lock = fresh_directory() / "packing.h5.lock";
  const pid_t child = child_holding(lock, [] { ::pause(); });
  ::kill(child, SIGKILL);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  int waits = 0;
  const FileLock mine(lock, [&] { ++waits; });
  EXPECT_EQ(waits, 0);
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
