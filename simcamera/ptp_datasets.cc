#include "simcamera/ptp_datasets.h"

#include "simcamera/ptp_codes.h"
#include "simcamera/ptp_data.h"

namespace brdfrig::simcamera {
namespace {

void Value(PtpWriter& w, std::uint16_t datatype, std::uint32_t value) {
  if (datatype == datatype::kUint16) {
    w.U16(static_cast<std::uint16_t>(value));
  } else {
    w.U32(value);
  }
}

}  // namespace

std::vector<std::uint8_t> DeviceInfoDataset(const DeviceDescription& device) {
  PtpWriter w;
  w.U16(100)   // PTP 1.00
      .U32(0)  // no vendor extension: libgphoto2 takes its generic PTP path
      .U16(0)
      .String("")
      .U16(0)  // functional mode: standard
      .U16Array(device.operations)
      .U16Array(device.events)
      .U16Array(device.properties)
      .U16Array(device.formats)  // capture formats
      .U16Array(device.formats)  // image formats
      .String(device.manufacturer)
      .String(device.model)
      .String(device.version)
      .String(device.serial);
  return w.Take();
}

std::vector<std::uint8_t> StorageInfoDataset(const StorageDescription& storage) {
  PtpWriter w;
  w.U16(4)     // removable RAM (a memory card)
      .U16(2)  // generic hierarchical file system
      .U16(0)  // read-write
      .U64(storage.capacity_bytes)
      .U64(storage.free_bytes)
      .U32(storage.free_images)
      .String(storage.description)
      .String(storage.label);
  return w.Take();
}

std::vector<std::uint8_t> ObjectInfoDataset(const ObjectDescription& object) {
  PtpWriter w;
  w.U32(object.storage)
      .U16(object.format)
      .U16(0)  // not protected
      .U32(object.size)
      .U16(0)  // no thumbnail
      .U32(0)
      .U32(0)
      .U32(0)
      .U32(object.width)
      .U32(object.height)
      .U32(object.bit_depth)
      .U32(object.parent)
      .U16(0)  // not an association
      .U32(0)
      .U32(0)  // sequence number
      .String(object.file_name)
      .String(object.capture_date)
      .String(object.capture_date)
      .String("");  // keywords
  return w.Take();
}

std::vector<std::uint8_t> DevicePropDescDataset(const EnumProperty& property) {
  PtpWriter w;
  w.U16(property.code).U16(property.datatype).U8(1);  // get/set
  Value(w, property.datatype, property.factory);
  Value(w, property.datatype, property.current);
  w.U8(2);  // enumeration form
  w.U16(static_cast<std::uint16_t>(property.values.size()));
  for (std::uint32_t v : property.values) Value(w, property.datatype, v);
  return w.Take();
}

std::vector<std::uint8_t> DevicePropValue(const EnumProperty& property) {
  PtpWriter w;
  Value(w, property.datatype, property.current);
  return w.Take();
}

}  // namespace brdfrig::simcamera
