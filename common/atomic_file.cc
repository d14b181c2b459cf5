#include "common/atomic_file.h"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <random>
#include <sstream>

#include "common/error.h"

namespace brdfrig {
namespace {

[[noreturn]] void ThrowSystem(const std::string& what, const std::filesystem::path& path, int err) {
  throw OutputError(what + " '" + path.string() + "': " + std::strerror(err));
}

// "TARGET.tmp-PID" (before temporaries had a random part) or "TARGET.tmp-PID-XXXXXXXX": the
// writer's pid, or 0 when `name` is not a temporary of `target_name`.
long TemporaryWriter(const std::string& name, const std::string& target_name) {
  const std::string prefix = target_name + ".tmp-";
  if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) return 0;
  const std::string rest = name.substr(prefix.size());
  const std::size_t dash = rest.find('-');
  const std::string pid = rest.substr(0, dash);
  if (pid.empty() || pid.size() > 9 || pid.find_first_not_of("0123456789") != std::string::npos) {
    return 0;
  }
  if (dash != std::string::npos) {
    const std::string random = rest.substr(dash + 1);
    if (random.size() != 8 || random.find_first_not_of("0123456789abcdef") != std::string::npos) {
      return 0;
    }
  }
  return std::stol(pid);
}

}  // namespace

int RemoveStaleTemporaries(const std::filesystem::path& target) {
  const std::filesystem::path dir = target.parent_path().empty() ? "." : target.parent_path();
  const std::string target_name = target.filename().string();
  const int dir_fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir_fd < 0) return 0;
  DIR* entries = ::fdopendir(dir_fd);
  if (entries == nullptr) {
    ::close(dir_fd);
    return 0;
  }
  int removed = 0;
  const std::time_t now = std::time(nullptr);
  while (const dirent* entry = ::readdir(entries)) {
    const long pid = TemporaryWriter(entry->d_name, target_name);
    if (pid <= 0) continue;
    struct stat info {};
    // Never followed: a symlink or anything else that is not a plain file of ours stays.
    if (::fstatat(dir_fd, entry->d_name, &info, AT_SYMLINK_NOFOLLOW) != 0 ||
        !S_ISREG(info.st_mode) || info.st_uid != ::geteuid()) {
      continue;
    }
    // A writer still running keeps its temporary; so does one written lately, which may be
    // another machine's (a shared file system) or another pid namespace's, whose pids say
    // nothing here.
    const bool running = ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;
    if (running || now - info.st_mtime < kStaleTemporaryAgeS) continue;
    removed += ::unlinkat(dir_fd, entry->d_name, 0) == 0;
  }
  ::closedir(entries);
  return removed;
}

void SyncDirectory(const std::filesystem::path& dir) {
  const std::filesystem::path target = dir.empty() ? "." : dir;
  const int fd = ::open(target.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) ThrowSystem("cannot open directory", target, errno);
  const int rc = ::fsync(fd);
  const int err = errno;
  ::close(fd);
  if (rc != 0) ThrowSystem("cannot sync directory", target, err);
}

std::filesystem::path WriteTemporaryAndSync(const std::filesystem::path& target,
                                            std::span<const std::byte> bytes) {
  // Temporaries a killed writer left beside this output go first: nothing else ever would.
  RemoveStaleTemporaries(target);
  // A fresh name each try, created only if nothing (not even a dangling symlink) is there.
  std::random_device random;
  std::filesystem::path path;
  int fd = -1;
  for (int attempt = 0; fd < 0; ++attempt) {
    char suffix[32];
    std::snprintf(suffix, sizeof suffix, ".tmp-%d-%08x", static_cast<int>(::getpid()),
                  static_cast<unsigned>(random()));
    path = target;
    path += suffix;
    fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd < 0 && (errno != EEXIST || attempt >= 100)) ThrowSystem("cannot create", path, errno);
  }
  std::size_t written = 0;
  while (written < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
    if (n < 0) {
      if (errno == EINTR) continue;
      const int err = errno;
      ::close(fd);
      ::unlink(path.c_str());
      ThrowSystem("cannot write", path, err);
    }
    written += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0 || ::close(fd) != 0) {
    const int err = errno;
    ::unlink(path.c_str());
    ThrowSystem("cannot flush", path, err);
  }
  return path;
}

void RenameAndSync(const std::filesystem::path& from, const std::filesystem::path& to) {
  if (::rename(from.c_str(), to.c_str()) != 0) {
    const int err = errno;
    ::unlink(from.c_str());
    ThrowSystem("cannot rename into place", to, err);
  }
  SyncDirectory(to.parent_path());
}

void CreateDirectories(const std::filesystem::path& dir) {
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error) {
    throw OutputError("cannot create directory '" + dir.string() + "': " + error.message());
  }
}

void WriteFileAtomically(const std::filesystem::path& path, std::span<const std::byte> bytes) {
  RenameAndSync(WriteTemporaryAndSync(path, bytes), path);
}

void WriteFileAtomically(const std::filesystem::path& path, std::string_view text) {
  WriteFileAtomically(path, std::as_bytes(std::span(text.data(), text.size())));
}

std::string ReadFileToString(const std::filesystem::path& path, std::size_t max_bytes) {
  // O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer forever.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    throw FileError(path.string(), std::string("cannot open file: ") + std::strerror(errno));
  }
  struct FdCloser {
    int fd;
    ~FdCloser() { ::close(fd); }
  } closer{fd};
  struct stat info {};
  if (::fstat(fd, &info) != 0 || !S_ISREG(info.st_mode)) {
    throw FileError(path.string(), "not a regular file (a directory, FIFO or device is not read)");
  }
  if (static_cast<std::uintmax_t>(info.st_size) > max_bytes) {
    throw FileError(path.string(), "file is " + std::to_string(info.st_size) +
                                       " bytes, more than the " + std::to_string(max_bytes) +
                                       " an input file may have");
  }
  std::string text;
  char buffer[65536];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw FileError(path.string(), std::string("read error: ") + std::strerror(errno));
    if (n == 0) break;
    // The file may grow while it is read (a proc file, a log): the cap holds all the same.
    if (text.size() + static_cast<std::size_t>(n) > max_bytes) {
      throw FileError(path.string(), "file grew past the " + std::to_string(max_bytes) +
                                         " bytes an input file may have");
    }
    text.append(buffer, static_cast<std::size_t>(n));
  }
  return text;
}

}  // namespace brdfrig
