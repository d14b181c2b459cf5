// Little-endian PTP datasets: the writer and reader for the field types PTP uses (integers,
// UCS-2 strings with a length byte, arrays with a 32-bit count).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace brdfrig::simcamera {

class PtpWriter {
 public:
  PtpWriter& U8(std::uint8_t v) { return Int(v, 1); }
  PtpWriter& U16(std::uint16_t v) { return Int(v, 2); }
  PtpWriter& U32(std::uint32_t v) { return Int(v, 4); }
  PtpWriter& U64(std::uint64_t v) { return Int(v, 8); }
  // A PTP string: number of UCS-2 characters including the terminating zero (0 for the empty
  // string), then the characters. Only ASCII text is written.
  PtpWriter& String(const std::string& text);
  PtpWriter& U16Array(const std::vector<std::uint16_t>& values);
  PtpWriter& U32Array(const std::vector<std::uint32_t>& values);
  // NUL-terminated UCS-2 without a length byte (the PTP/IP init packets' friendly name).
  PtpWriter& Ucs2z(const std::string& text);
  PtpWriter& Bytes(const std::vector<std::uint8_t>& bytes);

  const std::vector<std::uint8_t>& bytes() const { return bytes_; }
  std::vector<std::uint8_t> Take() { return std::move(bytes_); }

 private:
  PtpWriter& Int(std::uint64_t value, int size);
  std::vector<std::uint8_t> bytes_;
};

// Reads fields in order; a read past the end throws brdfrig::Error (a malformed packet).
class PtpReader {
 public:
  explicit PtpReader(const std::vector<std::uint8_t>& bytes, std::size_t offset = 0)
      : bytes_(bytes), at_(offset) {}
  std::uint16_t U16() { return static_cast<std::uint16_t>(Int(2)); }
  std::uint32_t U32() { return static_cast<std::uint32_t>(Int(4)); }
  std::uint64_t U64() { return Int(8); }
  std::size_t left() const { return bytes_.size() - at_; }

 private:
  std::uint64_t Int(int size);
  const std::vector<std::uint8_t>& bytes_;
  std::size_t at_;
};

}  // namespace brdfrig::simcamera
