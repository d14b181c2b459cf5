#include "simcamera/ptp_data.h"

#include "common/error.h"

namespace brdfrig::simcamera {

PtpWriter& PtpWriter::Int(std::uint64_t value, int size) {
  for (int i = 0; i < size; ++i) bytes_.push_back(static_cast<std::uint8_t>(value >> (8 * i)));
  return *this;
}

PtpWriter& PtpWriter::String(const std::string& text) {
  if (text.empty()) return U8(0);
  // The length byte counts the terminating zero and cannot exceed 255.
  const std::string cut = text.substr(0, 254);
  U8(static_cast<std::uint8_t>(cut.size() + 1));
  for (char c : cut) U16(static_cast<std::uint8_t>(c));
  return U16(0);
}

PtpWriter& PtpWriter::Ucs2z(const std::string& text) {
  for (char c : text) U16(static_cast<std::uint8_t>(c));
  return U16(0);
}

PtpWriter& PtpWriter::U16Array(const std::vector<std::uint16_t>& values) {
  U32(static_cast<std::uint32_t>(values.size()));
  for (std::uint16_t v : values) U16(v);
  return *this;
}

PtpWriter& PtpWriter::U32Array(const std::vector<std::uint32_t>& values) {
  U32(static_cast<std::uint32_t>(values.size()));
  for (std::uint32_t v : values) U32(v);
  return *this;
}

PtpWriter& PtpWriter::Bytes(const std::vector<std::uint8_t>& bytes) {
  bytes_.insert(bytes_.end(), bytes.begin(), bytes.end());
  return *this;
}

std::uint64_t PtpReader::Int(int size) {
  if (left() < static_cast<std::size_t>(size)) {
    throw Error("malformed PTP data: a " + std::to_string(size) + "-byte field at offset " +
                std::to_string(at_) + " runs past the end (" + std::to_string(bytes_.size()) +
                " bytes)");
  }
  std::uint64_t value = 0;
  for (int i = 0; i < size; ++i) value |= static_cast<std::uint64_t>(bytes_[at_ + i]) << (8 * i);
  at_ += static_cast<std::size_t>(size);
  return value;
}

}  // namespace brdfrig::simcamera
