#include "acquire/test_hooks.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <string>

#include "common/error.h"

namespace brdfrig::acquire::test_hooks {
namespace {

int EnvInt(const char* name) {
  const char* value = std::getenv(name);
  return value ? std::atoi(value) : 0;
}

std::atomic<int> kill_at{EnvInt("BRDFRIG_TEST_KILL_AT")};
std::atomic<int> points{0};
std::atomic<int> fail_write_at{EnvInt("BRDFRIG_TEST_FAIL_WRITE_AT")};
std::atomic<int> writes{0};

}  // namespace

void KillPoint(const char* phase) {
  const int target = kill_at.load(std::memory_order_relaxed);
  if (target <= 0) return;
  if (points.fetch_add(1) + 1 != target) return;
  if (const char* log = std::getenv("BRDFRIG_TEST_KILL_LOG")) {
    const int fd = ::open(log, O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (fd >= 0) {
      const std::string line = std::string(phase) + "\n";
      [[maybe_unused]] const ssize_t n = ::write(fd, line.data(), line.size());
      ::close(fd);
    }
  }
  ::kill(::getpid(), SIGKILL);
}

void BeforeFrameWrite() {
  const int target = fail_write_at.load(std::memory_order_relaxed);
  if (target <= 0) return;
  if (writes.fetch_add(1) + 1 == target) {
    throw Error(std::string("cannot write frame: ") + std::strerror(ENOSPC) +
                " (injected by BRDFRIG_TEST_FAIL_WRITE_AT)");
  }
}

void SetFailWriteAt(int n) {
  writes = 0;
  fail_write_at = n;
}

}  // namespace brdfrig::acquire::test_hooks
