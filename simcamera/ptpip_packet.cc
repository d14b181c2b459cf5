#include "simcamera/ptpip_packet.h"

#include <poll.h>
#include <sys/socket.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "common/error.h"
#include "simcamera/packet_stream.h"
#include "simcamera/ptp_data.h"

namespace brdfrig::simcamera {
namespace {

constexpr std::uint32_t kHeaderBytes = kPacketHeaderBytes;

// 1: data is ready; 0: timeout; -1: error.
int WaitReadable(int fd, std::chrono::milliseconds timeout) {
  pollfd p{fd, POLLIN, 0};
  for (;;) {
    const int n = poll(&p, 1, static_cast<int>(timeout.count()));
    if (n < 0 && errno == EINTR) continue;
    return n;
  }
}

// Reads exactly `size` bytes; false on EOF or error before the end.
bool ReadExactly(int fd, std::uint8_t* out, std::size_t size, std::chrono::milliseconds timeout) {
  std::size_t done = 0;
  while (done < size) {
    if (WaitReadable(fd, timeout) <= 0) return false;
    const ssize_t n = recv(fd, out + done, size - done, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

std::uint32_t Le32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
         static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
}

// Writes every byte on a blocking socket; false when the peer is gone (never raises SIGPIPE).
bool WriteAll(int fd, const std::vector<std::uint8_t>& bytes) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = send(fd, bytes.data() + done, bytes.size() - done, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

Packet Expect(std::optional<Packet> packet, const char* what) {
  if (!packet) throw Error(std::string("PTP/IP: the connection closed while waiting for ") + what);
  return std::move(*packet);
}

}  // namespace

std::optional<Packet> ReadPacket(int fd, std::chrono::milliseconds timeout) {
  std::uint8_t header[kHeaderBytes];
  if (WaitReadable(fd, timeout) <= 0) return std::nullopt;
  {
    // The first byte decides between an orderly close and a packet.
    const ssize_t n = recv(fd, header, 1, 0);
    if (n <= 0) return std::nullopt;
  }
  if (!ReadExactly(fd, header + 1, kHeaderBytes - 1, timeout)) {
    throw Error("PTP/IP: the connection broke inside a packet header");
  }
  const std::uint32_t length = Le32(header);
  if (length < kHeaderBytes || length > kMaxIncomingPacket) {
    throw Error("PTP/IP: bad packet length " + std::to_string(length));
  }
  Packet packet;
  packet.type = static_cast<PacketType>(Le32(header + 4));
  packet.payload.resize(length - kHeaderBytes);
  if (!ReadExactly(fd, packet.payload.data(), packet.payload.size(), timeout)) {
    throw Error("PTP/IP: the connection broke inside a packet of " + std::to_string(length) +
                " bytes");
  }
  return packet;
}

std::vector<std::uint8_t> EncodePacket(PacketType type, const std::vector<std::uint8_t>& payload) {
  PtpWriter w;
  w.U32(static_cast<std::uint32_t>(payload.size() + kHeaderBytes))
      .U32(static_cast<std::uint32_t>(type))
      .Bytes(payload);
  return w.Take();
}

bool WritePacket(int fd, PacketType type, const std::vector<std::uint8_t>& payload) {
  return WriteAll(fd, EncodePacket(type, payload));
}

OperationRequest ParseOperationRequest(const Packet& packet) {
  PtpReader r(packet.payload);
  OperationRequest request;
  request.data_phase = r.U32();
  request.code = r.U16();
  request.transaction = r.U32();
  while (r.left() >= 4 && request.params.size() < 5) request.params.push_back(r.U32());
  return request;
}

InitCommandRequest ParseInitCommandRequest(const Packet& packet) {
  if (packet.payload.size() < 16) throw Error("PTP/IP: init command request without a GUID");
  InitCommandRequest request;
  request.guid.assign(packet.payload.begin(), packet.payload.begin() + 16);
  // The name is NUL-terminated UCS-2 followed by the protocol version.
  for (std::size_t i = 16; i + 1 < packet.payload.size(); i += 2) {
    const std::uint16_t c =
        static_cast<std::uint16_t>(packet.payload[i] | packet.payload[i + 1] << 8);
    if (c == 0) break;
    request.name.push_back(c < 128 ? static_cast<char>(c) : '?');
  }
  return request;
}

std::vector<std::uint8_t> InitCommandAckPayload(std::uint32_t connection,
                                                const std::vector<std::uint8_t>& guid,
                                                const std::string& name) {
  PtpWriter w;
  w.U32(connection).Bytes(guid).Ucs2z(name).U32(0x00010000);  // protocol version 1.0
  return w.Take();
}

std::vector<std::uint8_t> ResponsePayload(std::uint16_t code, std::uint32_t transaction,
                                          const std::vector<std::uint32_t>& params) {
  PtpWriter w;
  w.U16(code).U32(transaction);
  for (std::uint32_t p : params) w.U32(p);
  return w.Take();
}

std::vector<std::uint8_t> EventPayload(std::uint16_t code, std::uint32_t transaction,
                                       const std::vector<std::uint32_t>& params) {
  return ResponsePayload(code, transaction, params);  // the same layout
}

std::vector<std::uint8_t> EncodeDataPhase(std::uint32_t transaction,
                                          const std::vector<std::uint8_t>& data,
                                          std::size_t chunk) {
  PtpWriter start;
  start.U32(transaction).U64(data.size());
  std::vector<std::uint8_t> out = EncodePacket(PacketType::kStartData, start.bytes());
  std::size_t at = 0;
  do {
    const std::size_t n = std::min(chunk, data.size() - at);
    const bool last = at + n == data.size();
    PtpWriter piece;
    piece.U32(static_cast<std::uint32_t>(n + 4 + kHeaderBytes))
        .U32(static_cast<std::uint32_t>(last ? PacketType::kEndData : PacketType::kData))
        .U32(transaction);
    out.insert(out.end(), piece.bytes().begin(), piece.bytes().end());
    out.insert(out.end(), data.begin() + static_cast<std::ptrdiff_t>(at),
               data.begin() + static_cast<std::ptrdiff_t>(at + n));
    at += n;
  } while (at < data.size());
  return out;
}

bool WriteDataPhase(int fd, std::uint32_t transaction, const std::vector<std::uint8_t>& data,
                    std::size_t chunk) {
  return WriteAll(fd, EncodeDataPhase(transaction, data, chunk));
}

std::vector<std::uint8_t> ReadDataPhase(int fd, std::uint32_t transaction,
                                        std::chrono::milliseconds timeout) {
  IncomingDataPhase phase(transaction);
  while (!phase.Add(Expect(ReadPacket(fd, timeout), "data"))) {
  }
  return phase.Take();
}

}  // namespace brdfrig::simcamera
