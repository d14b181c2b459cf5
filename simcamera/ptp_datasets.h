// The PTP datasets the simulated camera sends (ISO 15740 section 5): DeviceInfo, StorageInfo,
// ObjectInfo, DevicePropDesc and a property value, each encoded little-endian.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace brdfrig::simcamera {

struct DeviceDescription {
  std::string manufacturer;
  std::string model;
  std::string version;
  std::string serial;
  std::vector<std::uint16_t> operations;
  std::vector<std::uint16_t> events;
  std::vector<std::uint16_t> properties;
  std::vector<std::uint16_t> formats;  // capture and image formats alike
};
std::vector<std::uint8_t> DeviceInfoDataset(const DeviceDescription& device);

struct StorageDescription {
  std::uint64_t capacity_bytes = 0;
  std::uint64_t free_bytes = 0;
  std::uint32_t free_images = 0;
  std::string description;
  std::string label;
};
std::vector<std::uint8_t> StorageInfoDataset(const StorageDescription& storage);

struct ObjectDescription {
  std::uint32_t storage = 0;
  std::uint16_t format = 0;
  std::uint32_t size = 0;
  std::uint32_t width = 0, height = 0, bit_depth = 0;
  std::uint32_t parent = 0;  // 0: the storage's root
  std::string file_name;
  std::string capture_date;  // "YYYYMMDDThhmmss"
};
std::vector<std::uint8_t> ObjectInfoDataset(const ObjectDescription& object);

// A device property whose value is one of an enumerated list (form flag 2), read-write.
struct EnumProperty {
  std::uint16_t code = 0;
  std::uint16_t datatype = 0;  // UINT16 or UINT32
  std::uint32_t factory = 0;
  std::uint32_t current = 0;
  std::vector<std::uint32_t> values;
};
std::vector<std::uint8_t> DevicePropDescDataset(const EnumProperty& property);
std::vector<std::uint8_t> DevicePropValue(const EnumProperty& property);

}  // namespace brdfrig::simcamera
