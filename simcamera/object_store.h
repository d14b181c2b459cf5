// The simulated camera's memory card: captured files by object handle, a capacity in files
// (what makes "card full" happen), and the file names a camera would give them.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace brdfrig::simcamera {

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
  std::uint64_t bytes_used() const;
  // Files the card holds at most; < 0: unlimited.
  int capacity_files() const { return capacity_files_; }
  void set_capacity_files(int files) { capacity_files_ = files; }
  // Whether `more` further files fit.
  bool Fits(std::size_t more) const;

  // The next shot's file stem, "IMG_0001" ... (counts shots, not files).
  std::string NextStem();

 private:
  std::map<std::uint32_t, StoredObject> objects_;
  std::uint32_t next_handle_ = 1;
  int shots_ = 0;
  int capacity_files_ = -1;
};

}  // namespace brdfrig::simcamera
