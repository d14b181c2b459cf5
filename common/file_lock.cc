#include "common/file_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <utility>

#include "common/error.h"

namespace brdfrig {
namespace {

// Opens an existing lock file before trying to create one: in a sticky world-writable
// directory (/run/lock) the kernel refuses O_CREAT on another user's file
// (fs.protected_regular), while a plain open of it works.
int OpenLockFile(const std::filesystem::path& file) {
  for (int attempt = 0; attempt < 3; ++attempt) {
    int fd = ::open(file.c_str(), O_RDWR | O_CLOEXEC | O_NOFOLLOW);
    if (fd >= 0 || errno != ENOENT) return fd;
    fd = ::open(file.c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW, 0666);
    if (fd >= 0) {
      ::fchmod(fd, 0666);  // past the umask: the next owner may be another user
      return fd;
    }
    if (errno != EEXIST) return fd;
  }
  return -1;
}

std::string Holder(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  return line.empty() ? "another process" : line;
}

}  // namespace

std::string ThisProcessDescription() {
  std::ifstream in("/proc/self/cmdline", std::ios::binary);
  std::string command((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  while (!command.empty() && command.back() == '\0') command.pop_back();
  for (char& c : command) {
    if (c == '\0' || c == '\n') c = ' ';
  }
  if (command.size() > 300) command = command.substr(0, 300) + "...";
  return "pid " + std::to_string(::getpid()) + " (" + command + ")";
}

FileLock FileLock::Acquire(const std::filesystem::path& file, const std::string& what) {
  const int fd = OpenLockFile(file);
  if (fd < 0) {
    throw Error("cannot open the lock file " + file.string() + " for " + what + ": " +
                std::strerror(errno));
  }
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    ::close(fd);
    if (error != EWOULDBLOCK) {
      throw Error("cannot lock " + file.string() + " for " + what + ": " + std::strerror(error));
    }
    throw Error(what + " is in use by " + Holder(file) + " (lock file " + file.string() + ")");
  }
  FileLock lock;
  lock.fd_ = fd;
  const std::string holder = ThisProcessDescription() + "\n";
  // Best effort: the lock is what counts, the text only names the holder in messages.
  if (::ftruncate(fd, 0) == 0) {
    [[maybe_unused]] const ssize_t written = ::pwrite(fd, holder.data(), holder.size(), 0);
  }
  return lock;
}

FileLock::FileLock(FileLock&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}

FileLock& FileLock::operator=(FileLock&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = std::exchange(other.fd_, -1);
  }
  return *this;
}

FileLock::~FileLock() {
  if (fd_ >= 0) ::close(fd_);
}

}  // namespace brdfrig
