// A PTP/IP initiator for the server's tests, spoken packet by packet over blocking sockets:
// connect, the init handshake, operations with and without data. Every read has a deadline,
// so a server that never answers fails the test instead of hanging it.
#pragma once

#include <arpa/inet.h>
#include <dirent.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "simcamera/ptp_codes.h"
#include "simcamera/ptp_data.h"
#include "simcamera/ptpip_packet.h"

namespace brdfrig::simcamera::testing {

inline constexpr std::chrono::milliseconds kWait{3000};

// A connected socket to 127.0.0.1:port (-1 when the connection failed); `receive_buffer` > 0
// shrinks the socket's receive buffer first (a client that reads slowly fills it at once).
inline int ConnectTo(int port, int receive_buffer = 0) {
  const int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  const timeval limit{5, 0};
  setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &limit, sizeof limit);
  setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &limit, sizeof limit);
  if (receive_buffer > 0) {
    setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &receive_buffer, sizeof receive_buffer);
  }
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  inet_pton(AF_INET, "127.0.0.1", &address.sin_addr);
  if (connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) {
    close(fd);
    return -1;
  }
  return fd;
}

inline std::vector<std::uint8_t> InitCommandPayload() {
  PtpWriter init;
  init.Bytes(std::vector<std::uint8_t>(16, 7)).Ucs2z("test").U32(0x00010000);
  return init.Take();
}

// The init command request on `command`; returns the connection number of the ack (0: none).
inline std::uint32_t InitCommand(int command) {
  if (!WritePacket(command, PacketType::kInitCommandRequest, InitCommandPayload())) return 0;
  const std::optional<Packet> ack = ReadPacket(command, kWait);
  if (!ack || ack->type != PacketType::kInitCommandAck || ack->payload.size() < 4) return 0;
  return PtpReader(ack->payload).U32();
}

// The init event request for connection `number`; true when acknowledged.
inline bool InitEvent(int event, std::uint32_t number) {
  PtpWriter request;
  request.U32(number);
  if (!WritePacket(event, PacketType::kInitEventRequest, request.bytes())) return false;
  const std::optional<Packet> ack = ReadPacket(event, kWait);
  return ack && ack->type == PacketType::kInitEventAck;
}

// Sends an operation (with `data` to the camera when given) and returns the response code
// (0: no response), collecting a data phase from the camera into `received` when given.
inline std::uint16_t Operation(int command, std::uint16_t code, std::uint32_t transaction,
                               const std::vector<std::uint32_t>& params = {},
                               const std::vector<std::uint8_t>* data = nullptr,
                               std::vector<std::uint8_t>* received = nullptr) {
  PtpWriter request;
  request.U32(data ? kDataPhaseToCamera : 1).U16(code).U32(transaction);
  for (std::uint32_t p : params) request.U32(p);
  if (!WritePacket(command, PacketType::kOperationRequest, request.bytes())) return 0;
  if (data && !WriteDataPhase(command, transaction, *data)) return 0;
  for (;;) {
    std::optional<Packet> packet;
    try {
      packet = ReadPacket(command, kWait);
    } catch (const std::exception&) {
      return 0;
    }
    if (!packet) return 0;
    if ((packet->type == PacketType::kData || packet->type == PacketType::kEndData) && received) {
      received->insert(received->end(), packet->payload.begin() + 4, packet->payload.end());
    }
    if (packet->type == PacketType::kOperationResponse) {
      PtpReader r(packet->payload);
      const std::uint16_t rc = r.U16();
      if (r.U32() != transaction) return 0;
      return rc;
    }
  }
}

// Whether the server closed `fd`: the read sees an orderly close or a reset (not a timeout).
inline bool ClosedByServer(int fd) {
  char buffer[4096];
  for (;;) {
    const ssize_t n = recv(fd, buffer, sizeof buffer, 0);
    if (n > 0) continue;  // whatever the server sent before closing
    return n == 0 || errno == ECONNRESET;
  }
}

// Open file descriptors of this process.
inline int OpenDescriptors() {
  int count = 0;
  if (DIR* dir = opendir("/proc/self/fd")) {
    while (readdir(dir) != nullptr) ++count;
    closedir(dir);
  }
  return count - 3;  // ".", ".." and the directory's own descriptor
}

// An initiator with its command and event connections.
struct Initiator {
  int command = -1;
  int event = -1;
  // `receive_buffer`: see ConnectTo (the command connection's).
  explicit Initiator(int port, int receive_buffer = 0) {
    command = ConnectTo(port, receive_buffer);
    const std::uint32_t number = command < 0 ? 0 : InitCommand(command);
    EXPECT_NE(number, 0u) << "no init command ack";
    event = ConnectTo(port);
    EXPECT_TRUE(event >= 0 && InitEvent(event, number)) << "no init event ack";
  }
  ~Initiator() {
    if (command >= 0) close(command);
    if (event >= 0) close(event);
  }
  Initiator(const Initiator&) = delete;
  Initiator& operator=(const Initiator&) = delete;
};

}  // namespace brdfrig::simcamera::testing
