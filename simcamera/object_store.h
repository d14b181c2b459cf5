// The simulated camera's memory card: captured files by object handle, a capacity in files
// and in bytes (what makes "card full" happen), and the file names a camera would give them.
// The card lives in memory, so its byte capacity is what bounds the camera's memory.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace brdfrig::simcamera {

// The card's size in memory unless told otherwise: some hundred RAW+JPEG pairs of a
// full-resolution scene, thousands of the tests' small ones.
inline constexpr std::uint64_t kDefaultCardBytes = 1ull << 30;

struct StoredObject {
  std::uint32_t handle = 0;
  std::string file_name;  // e.g. "IMG_0007.DNG"
  std::uint16_t format = 0;
  std::vector<std::uint8_t> bytes;
  std::uint32_t width = 0, height = 0, bit_depth = 0;
  std::string capture_date;
};

class ObjectStore {
 public:
  // Stores a file under a new handle (handles are never reused) and returns the handle.
  std::uint32_t Add(StoredObject object);
  const StoredObject* Find(std::uint32_t handle) const;
  bool Remove(std::uint32_t handle);
  // Handles in capture order; `format` 0 means every format.
  std::vector<std::uint32_t> Handles(std::uint16_t format = 0) const;

  std::size_t files() const { return objects_.size(); }
  std::uint64_t bytes_used() const { return bytes_used_; }
  // Files the card holds at most; < 0: unlimited.
  int capacity_files() const { return capacity_files_; }
  void set_capacity_files(int files) { capacity_files_ = files; }
  // Bytes the card holds at most.
  std::uint64_t capacity_bytes() const { return capacity_bytes_; }
  void set_capacity_bytes(std::uint64_t bytes) { capacity_bytes_ = bytes; }
  // Whether `more_files` further files of `more_bytes` in all fit.
  bool Fits(std::size_t more_files, std::uint64_t more_bytes = 0) const;

  // The next shot's file stem, "IMG_0001" ... (counts shots, not files).
  std::string NextStem();

 private:
  std::map<std::uint32_t, StoredObject> objects_;
  std::uint32_t next_handle_ = 1;
  int shots_ = 0;
  int capacity_files_ = -1;
  std::uint64_t capacity_bytes_ = kDefaultCardBytes;
  std::uint64_t bytes_used_ = 0;
};

}  // namespace brdfrig::simcamera
