// Incremental PTP/IP parsing for a non-blocking server: a packet assembler that is fed whatever
// bytes a socket gives and yields whole packets, and the data phase to the camera (start data,
// data..., end data) checked packet by packet. Both hold at most one packet or one announced
// data phase, so what a client sends can never grow the camera's memory beyond those limits.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "simcamera/ptpip_packet.h"

namespace brdfrig::simcamera {

// Larger than any packet or data phase this camera accepts (requests, small settings): a
// bigger length is a desynchronized or hostile stream, not something to allocate.
inline constexpr std::uint32_t kMaxIncomingPacket = 1 << 20;
inline constexpr std::uint32_t kPacketHeaderBytes = 8;

class PacketAssembler {
 public:
  // How many bytes to read next so that the buffer never runs past the current packet: the
  // rest of the header, then the rest of the payload. Never 0.
  std::size_t wanted() const;
  // Appends at most wanted() bytes; throws brdfrig::Error for a packet length out of range
  // (checked as soon as the header is complete, before anything is allocated for it).
  void Append(const std::uint8_t* bytes, std::size_t size);
  // The packet once it is complete (then the assembler starts the next one).
  std::optional<Packet> Take();
  // Whether part of a packet has arrived (a connection that stops here is stalled).
  bool mid_packet() const { return !buffer_.empty(); }

 private:
  std::uint32_t length() const;  // the header's length field; needs a complete header
  std::vector<std::uint8_t> buffer_;
};

// The data phase of an operation with data to the camera.
class IncomingDataPhase {
 public:
  explicit IncomingDataPhase(std::uint32_t transaction) : transaction_(transaction) {}
  // Takes the next packet of the phase; true once the end data arrived and the bytes add up to
  // the announced total. Throws brdfrig::Error when the stream leaves the protocol: another
  // packet type or transaction, a total over kMaxIncomingPacket, or more bytes than announced
  // (checked as they come, so a client cannot make the camera buffer more than the limit).
  bool Add(const Packet& packet);
  std::vector<std::uint8_t> Take() { return std::move(data_); }

 private:
  std::uint32_t transaction_;
  std::optional<std::uint64_t> total_;  // set by the start data packet
  std::vector<std::uint8_t> data_;
};

}  // namespace brdfrig::simcamera
