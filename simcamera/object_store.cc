#include "simcamera/object_store.h"

#include <cstdio>

namespace brdfrig::simcamera {

std::uint32_t ObjectStore::Add(StoredObject object) {
  object.handle = next_handle_++;
  const std::uint32_t handle = object.handle;
  bytes_used_ += object.bytes.size();
  objects_[handle] = std::move(object);
  return handle;
}

const StoredObject* ObjectStore::Find(std::uint32_t handle) const {
  const auto it = objects_.find(handle);
  return it == objects_.end() ? nullptr : &it->second;
}

bool ObjectStore::Remove(std::uint32_t handle) {
  const auto it = objects_.find(handle);
  if (it == objects_.end()) return false;
  bytes_used_ -= it->second.bytes.size();
  objects_.erase(it);
  return true;
}

std::vector<std::uint32_t> ObjectStore::Handles(std::uint16_t format) const {
  std::vector<std::uint32_t> out;
  for (const auto& [handle, object] : objects_) {
    if (format == 0 || object.format == format) out.push_back(handle);
  }
  return out;
}

bool ObjectStore::Fits(std::size_t more_files, std::uint64_t more_bytes) const {
  if (bytes_used_ + more_bytes > capacity_bytes_) return false;
  return capacity_files_ < 0 ||
         objects_.size() + more_files <= static_cast<std::size_t>(capacity_files_);
}

std::string ObjectStore::NextStem() {
  char stem[32];
  std::snprintf(stem, sizeof stem, "IMG_%04d", ++shots_ % 10000);
  return stem;
}

}  // namespace brdfrig::simcamera
