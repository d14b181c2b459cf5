// PTP/IP packets on a TCP stream: a 32-bit length (header included) and a 32-bit type, then
// the payload. Reading and writing one packet, and the payloads of the packets the camera
// side parses or builds.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "simcamera/ptp_codes.h"

namespace brdfrig::simcamera {

struct Packet {
  PacketType type = PacketType::kInitFail;
  std::vector<std::uint8_t> payload;
};

// Blocking reads and writes, for initiators (the tests' clients); the server reads through
// packet_stream.h and writes the Encode... bytes without blocking.
//
// Reads one whole packet from a blocking socket. Returns nullopt when the peer closed the
// connection (or `timeout` passed before the first byte); throws brdfrig::Error for a
// malformed header or a connection that breaks inside a packet.
std::optional<Packet> ReadPacket(int fd, std::chrono::milliseconds timeout);

// A packet type as messages show it: its number, which the PTP/IP specification tables by.
inline std::string PacketTypeName(PacketType type) {
  return std::to_string(static_cast<std::uint32_t>(type));
}

// One packet's bytes: header and payload.
std::vector<std::uint8_t> EncodePacket(PacketType type, const std::vector<std::uint8_t>& payload);
// Writes one packet; false when the peer is gone (never raises SIGPIPE).
bool WritePacket(int fd, PacketType type, const std::vector<std::uint8_t>& payload);

struct OperationRequest {
  std::uint32_t data_phase = 1;
  std::uint16_t code = 0;
  std::uint32_t transaction = 0;
  std::vector<std::uint32_t> params;  // at most 5
};
OperationRequest ParseOperationRequest(const Packet& packet);

struct InitCommandRequest {
  std::vector<std::uint8_t> guid;  // 16 bytes: the initiator's identity
  std::string name;                // the initiator's friendly name (ASCII part)
};
InitCommandRequest ParseInitCommandRequest(const Packet& packet);

std::vector<std::uint8_t> InitCommandAckPayload(std::uint32_t connection,
                                                const std::vector<std::uint8_t>& guid,
                                                const std::string& name);
std::vector<std::uint8_t> ResponsePayload(std::uint16_t code, std::uint32_t transaction,
                                          const std::vector<std::uint32_t>& params = {});
std::vector<std::uint8_t> EventPayload(std::uint16_t code, std::uint32_t transaction,
                                       const std::vector<std::uint32_t>& params = {});

// A data phase from the camera: start data (total length), then data packets of at most
// `chunk` bytes, the last one as end data.
std::vector<std::uint8_t> EncodeDataPhase(std::uint32_t transaction,
                                          const std::vector<std::uint8_t>& data,
                                          std::size_t chunk = 1 << 16);
// Sends EncodeDataPhase's bytes. False when the peer is gone.
bool WriteDataPhase(int fd, std::uint32_t transaction, const std::vector<std::uint8_t>& data,
                    std::size_t chunk = 1 << 16);

// Reads a data phase to the camera (start data, data..., end data) for `transaction`.
// Throws brdfrig::Error when the stream does not follow the protocol (IncomingDataPhase).
std::vector<std::uint8_t> ReadDataPhase(int fd, std::uint32_t transaction,
                                        std::chrono::milliseconds timeout);

}  // namespace brdfrig::simcamera
