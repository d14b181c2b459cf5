// One TCP connection of the simulated camera, non-blocking: at most one incoming packet being
// assembled, the bytes still to send, and the times the server's deadlines are measured from.
// The server never waits on one connection, so a silent, dripping or non-reading peer costs
// only its own connection (docs/rig.md, "The simulated camera under bad clients").
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "simcamera/packet_stream.h"
#include "simcamera/ptp_responder.h"

namespace brdfrig::simcamera {

enum class ConnectionRole {
  kNewcomer,  // accepted, its init request not yet read
  kCommand,   // the initiator's command connection (one at a time)
  kEvent,     // the initiator's event connection
};

class PtpIpConnection {
 public:
  using Clock = std::chrono::steady_clock;

  // Takes ownership of `fd` and makes it non-blocking.
  PtpIpConnection(int fd, Clock::time_point now);
  ~PtpIpConnection();
  PtpIpConnection(const PtpIpConnection&) = delete;
  PtpIpConnection& operator=(const PtpIpConnection&) = delete;

  int fd() const { return fd_; }
  // Closes the socket at once (an evicted newcomer's descriptor is needed for the next one).
  void CloseSocket();

  // Reads what the socket holds, up to the end of the current packet, and returns the packet
  // once it is whole. Sets peer_closed() on an orderly close or a reset; throws brdfrig::Error
  // for a malformed header or a close inside a packet.
  std::optional<Packet> Receive(Clock::time_point now);
  bool peer_closed() const { return peer_closed_; }
  // Whether part of a packet has arrived, and since when.
  bool mid_packet() const { return in_.mid_packet(); }
  Clock::time_point packet_started() const { return packet_started_; }

  // Appends bytes to send, not before `not_before` (an injected response delay).
  void Queue(const std::vector<std::uint8_t>& bytes, Clock::time_point not_before);
  // Sends what the socket takes now; false when the peer is gone.
  bool Flush(Clock::time_point now);
  // Bytes queued and not yet sent.
  std::size_t unsent() const { return out_.size() - out_at_; }
  // Whether queued bytes may go out now (the response delay has passed).
  bool ready_to_send(Clock::time_point now) const { return unsent() > 0 && now >= send_at_; }
  // Since when queued bytes have waited for the peer to read (meaningful while ready_to_send).
  Clock::time_point last_progress() const { return last_progress_; }

  ConnectionRole role = ConnectionRole::kNewcomer;
  Clock::time_point accepted;
  std::uint32_t number = 0;  // the connection number of a command connection's ack
  bool closed = false;       // to be removed by the server
  bool close_when_sent = false;
  // Command connection: the operation whose data phase is being received.
  std::optional<OperationRequest> request;
  std::optional<IncomingDataPhase> data_in;
  Clock::time_point phase_started;
  // Command connection: work to run once the response has been sent (a capture's rendering)
  // and the transaction its events belong to.
  std::function<std::vector<PtpEvent>()> after;
  std::uint32_t after_transaction = 0;

 private:
  int fd_;
  PacketAssembler in_;
  Clock::time_point packet_started_{};
  bool peer_closed_ = false;
  std::vector<std::uint8_t> out_;
  std::size_t out_at_ = 0;
  Clock::time_point send_at_{};
  Clock::time_point last_progress_{};
};

}  // namespace brdfrig::simcamera
