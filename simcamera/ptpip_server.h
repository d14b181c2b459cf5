// A simulated network camera speaking PTP/IP (CIPA DC-005) on a loopback TCP port, so that
// libgphoto2's own ptp2 driver (port "ptpip:HOST:PORT") and the gphoto2 tool talk to it as to a
// Wi-Fi/Ethernet body: the initiator opens the command connection (Init Command Request with
// its GUID and name → Ack with ours), then the event connection to the same port (Init Event
// Request → Ack); operations, data phases and responses go over the first, events over the
// second. One initiator at a time: a new command connection replaces the old one, as a body
// does when the computer reconnects; the card and the settings survive it.
//
// Faults are injected for the next operations, to rehearse what the rig sees (docs/rig.md).
// One thread serves the sockets; the rest of the class may be used from any thread.
#pragma once

#include <atomic>
#include <chrono>
#include <mutex>
#include <string>
#include <thread>

#include "simcamera/ptp_responder.h"

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
  int operations = 0;
  int captures = 0;
  int busy = 0;
  int dropped = 0;
  int store_full = 0;
  int vanished = 0;
};

struct CameraServerOptions {
  std::string host = "127.0.0.1";
  int port = 0;  // 0: an ephemeral port (read it back with port())
  CameraOffer offer;
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
  void Listen();
  void Serve();
  void Accept();
  void ServeCommand();
  void CloseConnection();
  void SendEvents(const std::vector<PtpEvent>& events, std::uint32_t transaction);

  CameraServerOptions options_;
  int port_ = 0;
  int listener_ = -1;
  int command_ = -1;
  int event_ = -1;
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
