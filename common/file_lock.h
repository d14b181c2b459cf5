// An exclusive lock that says who holds it: flock() on a lock file whose content is the
// holder's pid and command line. The kernel drops the lock when the holder dies, so a crash
// never leaves anything locked; the content is only read to name the holder in the error.
#pragma once

#include <filesystem>
#include <string>

namespace brdfrig {

class FileLock {
 public:
  FileLock() = default;
  // Takes the lock without waiting, or throws brdfrig::Error "<what> is in use by pid N
  // (command) (lock file PATH)". The lock file's directory must exist.
  static FileLock Acquire(const std::filesystem::path& file, const std::string& what);

  FileLock(FileLock&& other) noexcept;
  FileLock& operator=(FileLock&& other) noexcept;
  ~FileLock();
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;

  bool held() const { return fd_ >= 0; }

 private:
  int fd_ = -1;
};

// "pid 1234 (brdfrig daemon --config d.yaml)": this process, as a lock file records it.
std::string ThisProcessDescription();

}  // namespace brdfrig
