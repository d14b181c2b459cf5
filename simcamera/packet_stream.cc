#include "simcamera/packet_stream.h"

#include <string>

#include "common/error.h"
#include "simcamera/ptp_data.h"

namespace brdfrig::simcamera {

std::uint32_t PacketAssembler::length() const {
  return static_cast<std::uint32_t>(buffer_[0]) | static_cast<std::uint32_t>(buffer_[1]) << 8 |
         static_cast<std::uint32_t>(buffer_[2]) << 16 |
         static_cast<std::uint32_t>(buffer_[3]) << 24;
}

std::size_t PacketAssembler::wanted() const {
  if (buffer_.size() < kPacketHeaderBytes) return kPacketHeaderBytes - buffer_.size();
  const std::size_t rest = length() - buffer_.size();
  return rest == 0 ? kPacketHeaderBytes : rest;  // 0: a whole packet waits to be taken
}

void PacketAssembler::Append(const std::uint8_t* bytes, std::size_t size) {
  if (size > wanted() || (buffer_.size() >= kPacketHeaderBytes && length() == buffer_.size())) {
    throw Error("PTP/IP: bytes beyond the current packet");  // a caller's bug, not the peer's
  }
  const bool header_was_complete = buffer_.size() >= kPacketHeaderBytes;
  buffer_.insert(buffer_.end(), bytes, bytes + size);
  if (!header_was_complete && buffer_.size() == kPacketHeaderBytes) {
    const std::uint32_t n = length();
    if (n < kPacketHeaderBytes || n > kMaxIncomingPacket) {
      throw Error("PTP/IP: bad packet length " + std::to_string(n));
    }
    buffer_.reserve(n);
  }
}

std::optional<Packet> PacketAssembler::Take() {
  if (buffer_.size() < kPacketHeaderBytes || buffer_.size() != length()) return std::nullopt;
  PtpReader r(buffer_, 4);
  Packet packet;
  packet.type = static_cast<PacketType>(r.U32());
  packet.payload.assign(buffer_.begin() + kPacketHeaderBytes, buffer_.end());
  buffer_.clear();
  return packet;
}

bool IncomingDataPhase::Add(const Packet& packet) {
  if (!total_) {
    if (packet.type != PacketType::kStartData) {
      throw Error("PTP/IP: expected start data, got packet type " + PacketTypeName(packet.type));
    }
    PtpReader r(packet.payload);
    if (r.U32() != transaction_) throw Error("PTP/IP: start data for another transaction");
    total_ = r.U64();
    if (*total_ > kMaxIncomingPacket) throw Error("PTP/IP: data phase too large for this camera");
    data_.reserve(static_cast<std::size_t>(*total_));
    return false;
  }
  if (packet.type != PacketType::kData && packet.type != PacketType::kEndData) {
    throw Error("PTP/IP: expected data, got packet type " + PacketTypeName(packet.type));
  }
  if (packet.payload.size() < 4) throw Error("PTP/IP: data packet without a transaction id");
  PtpReader r(packet.payload);
  if (r.U32() != transaction_) throw Error("PTP/IP: data for another transaction");
  // The running sum, not only the total at the end: a client announcing 4 bytes and sending
  // gigabytes is refused at the first packet past the total.
  const std::size_t piece = packet.payload.size() - 4;
  if (data_.size() + piece > *total_) {
    throw Error("PTP/IP: data phase announced " + std::to_string(*total_) +
                " bytes, got more than that");
  }
  data_.insert(data_.end(), packet.payload.begin() + 4, packet.payload.end());
  if (packet.type != PacketType::kEndData) return false;
  if (data_.size() != *total_) {
    throw Error("PTP/IP: data phase announced " + std::to_string(*total_) + " bytes, got " +
                std::to_string(data_.size()));
  }
  return true;
}

}  // namespace brdfrig::simcamera
