// A simulated network camera speaking PTP/IP (CIPA DC-005) on a loopback TCP port, so that
// libgphoto2's own ptp2 driver (port "ptpip:HOST:PORT") and the gphoto2 tool talk to it as to a
// Wi-Fi/Ethernet body: the initiator opens the command connection (Init Command Request with
// its GUID and name → Ack with ours), then the event connection to the same port (Init Event
// Request → Ack); operations, data phases and responses go over the first, events over the
// second. One initiator at a time: a new command connection replaces the old one, as a body
// does when the computer reconnects; the card and the settings survive it.
//
// Faults are injected for the next operations, to rehearse what the rig sees (docs/rig.md).
// One thread serves every socket without blocking on any (poll(), one state machine per
// connection, ptpip_connection.h): a newcomer that is silent, drips bytes, sends garbage or an
// init request without a GUID, a data phase larger than announced, or a peer that stops
// reading costs only its own connection, within the limits below; the established initiator
// keeps being served. The rest of the class may be used from any thread.
#pragma once

#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "simcamera/ptp_responder.h"
#include "simcamera/ptpip_connection.h"

namespace brdfrig::simcamera {

struct CameraFaults {
  // The next N downloads and deletions (GetObject, DeleteObject) answer DeviceBusy (0x2019),
  // as a body does while it writes the card. (Not InitiateCapture: libgphoto2 2.5.30's generic
  // capture ignores a failed InitiateCapture response and then waits for events forever.)
  int busy_responses = 0;
  // The next N settings (SetDevicePropValue) answer DeviceBusy.
  int busy_settings = 0;
  // Every response waits this long first. libgphoto2's PTP/IP socket timeout is 2.5 s: below
  // it the camera is merely slow, above it each operation times out.
  double response_delay_s = 0;
  // The next N downloads (GetObject) lose the connection after the start-data packet.
  int drop_downloads = 0;
  // The card holds at most this many files (< 0: unlimited). A capture that does not fit is
  // answered StoreFull (0x200C) with a StoreFull event.
  int card_capacity_files = -1;
  // At the next InitiateCapture the camera vanishes: every connection closes and the port
  // refuses connections for this long, then it listens again (same port, card kept).
  double vanish_s = 0;
};

struct CameraServerCounters {
  int connections = 0;  // command connections accepted (initiator sessions)
  int refused = 0;      // connections closed for breaking the protocol or a limit
  int operations = 0;
  int captures = 0;
  int busy = 0;
  int dropped = 0;
  int store_full = 0;
  int vanished = 0;
};

// How long and how much one connection may cost. Tests set them small.
struct ConnectionLimits {
  // A newcomer must send its init request within this time.
  std::chrono::milliseconds init_timeout{5000};
  // A packet, once its first byte arrived, and a data phase to the camera must be complete
  // within this time.
  std::chrono::milliseconds packet_timeout{5000};
  // A peer that reads nothing of a queued reply for this long is closed (libgphoto2 waits
  // 2.5 s for an answer; a live initiator reads at once).
  std::chrono::milliseconds send_timeout{10000};
  // Newcomers waiting for their init request at most; one more closes the oldest of them
  // (a real initiator sends its request at once, so it is never the oldest for long). This
  // bounds the camera's descriptors whatever the number of clients: newcomers + command +
  // event connection + the listener.
  int max_newcomers = 16;
  // Events queued for an event connection that does not read, at most (bytes).
  std::size_t max_event_backlog = 1 << 16;
};

struct CameraServerOptions {
  std::string host = "127.0.0.1";
  int port = 0;  // 0: an ephemeral port (read it back with port())
  CameraOffer offer;
  ConnectionLimits limits;
  // What the card holds in memory, in bytes: a capture whose files (estimated by the previous
  // shot) no longer fit is refused with StoreFull like a full card, so a client that never
  // deletes cannot grow the camera's memory without bound (docs/rig.md).
  std::uint64_t card_bytes = kDefaultCardBytes;
};

class PtpIpCameraServer {
 public:
  // Starts listening at once; throws brdfrig::Error when the address cannot be bound.
  PtpIpCameraServer(CameraServerOptions options, ShotFunction shoot);
  ~PtpIpCameraServer();
  PtpIpCameraServer(const PtpIpCameraServer&) = delete;
  PtpIpCameraServer& operator=(const PtpIpCameraServer&) = delete;

  int port() const { return port_; }
  // libgphoto2's port path for this camera: "ptpip:127.0.0.1:15740" on the standard port,
  // "ptpip:127.0.0.1:PORT:PORT" (event channel on the same port) elsewhere.
  std::string PortPath() const;

  // Replaces the pending faults (card capacity applies from now on).
  void InjectFaults(const CameraFaults& faults);
  CameraServerCounters counters() const;
  ExposureSettings exposure() const;
  std::size_t files_on_card() const;

 private:
  using Clock = PtpIpConnection::Clock;
  void Listen();
  void Serve();
  void ServeOnce();
  void Accept(Clock::time_point now);
  void OnPacket(PtpIpConnection& c, Packet packet, Clock::time_point now);
  void OnNewcomer(PtpIpConnection& c, const Packet& packet, Clock::time_point now);
  void OnCommand(PtpIpConnection& c, const Packet& packet, Clock::time_point now);
  void Dispatch(PtpIpConnection& c, const OperationRequest& request,
                const std::vector<std::uint8_t>& data, Clock::time_point now);
  void RunAfterWork(PtpIpConnection& c, Clock::time_point now);
  void CheckDeadlines(PtpIpConnection& c, Clock::time_point now);
  void Close(PtpIpConnection& c, const std::string& why);
  void CloseAll();
  PtpIpConnection* Find(ConnectionRole role);

  CameraServerOptions options_;
  int port_ = 0;
  int listener_ = -1;
  std::vector<std::unique_ptr<PtpIpConnection>> connections_;  // the server thread's only
  // Connection numbers are drawn, not counted: an event request must name its command
  // connection's, and a client cannot guess it to take the initiator's events.
  std::mt19937 numbers_{std::random_device{}()};
  Clock::time_point accept_paused_until_{};          // after running out of descriptors
  std::chrono::steady_clock::time_point back_at_{};  // while vanished
  bool vanished_ = false;

  mutable std::mutex mutex_;  // guards responder_, faults_, counters_
  PtpResponder responder_;
  CameraFaults faults_;
  CameraServerCounters counters_;

  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace brdfrig::simcamera
