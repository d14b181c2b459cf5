// A simulated positioning drive behind a real Modbus server (libmodbus), for testing the real
// client (rig/modbus_axis.h) without hardware: on loopback TCP, or on a pseudo-terminal for RTU
// (the client opens pty_path() as its serial device). It implements a DriveProfile's register
// map with simple trapezoidal motion (speed, acceleration, position readback) in real time,
// and faults can be injected for the next requests or the next move.
//
// One thread owns the libmodbus context and answers every TCP client connected (up to
// kMaxTcpClients; a gateway serves several masters, e.g. the capture and a simulated camera
// reading positions), one request at a time.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "rig/drive_profile.h"

typedef struct _modbus modbus_t;
typedef struct _modbus_mapping_t modbus_mapping_t;

namespace brdfrig::sim {

// Faults for the next requests (counts are used up one request at a time) or the next move.
struct DriveFaults {
  int drop_responses = 0;         // no answer at all (the request is not applied either)
  int corrupt_responses = 0;      // answer with a bad CRC (RTU) or a bad MBAP header (TCP)
  int exception_responses = 0;    // answer with `exception_code` (request not applied)
  int exception_code = 6;         // Modbus exception: 6 = server busy, 2 = illegal address, ...
  double alarm_at_fraction = -1;  // next move raises `alarm_code` at this fraction of its travel
  int alarm_code = 0x30;          // AZ: 0x30 = overload
  double speed_factor = 1;        // < 1 makes moves slower than commanded (a stalled axis)
};

struct DriveServerCounters {
  int connections = 0;
  int requests = 0;
  int dropped = 0;
  int corrupted = 0;
  int exceptions = 0;
  int moves = 0;  // moves started by a trigger
  int stops = 0;
  int homes = 0;
  int alarm_resets = 0;
};

struct DriveServerOptions {
  enum class Transport { kTcp, kPty };
  Transport transport = Transport::kTcp;
  int tcp_port = 0;  // 0: an ephemeral port (read it back with port())
  int slave = 1;
  int32_t initial_position_steps = 0;
};

class ModbusDriveServer {
 public:
  // Starts serving at once; throws brdfrig::Error when the port or pty cannot be opened.
  ModbusDriveServer(rig::DriveProfile profile, DriveServerOptions options);
  ~ModbusDriveServer();
  ModbusDriveServer(const ModbusDriveServer&) = delete;
  ModbusDriveServer& operator=(const ModbusDriveServer&) = delete;

  int port() const { return port_; }                    // TCP
  const std::string& pty_path() const { return pty_; }  // RTU, e.g. /dev/pts/7
  std::string Endpoint() const;  // "tcp://127.0.0.1:PORT" or "rtu:/dev/pts/N"

  void InjectFaults(const DriveFaults& faults);
  DriveServerCounters counters() const;
  int32_t position_steps() const;
  bool moving();  // advances the simulated motion to now first
  bool alarm() const;
  bool coil(int address) const;

 private:
  struct Motion {
    double position = 0;  // steps
    double velocity = 0;  // steps/s, signed
    double target = 0;
    double speed = 0;         // steps/s (commanded, times the fault's speed factor)
    double acceleration = 0;  // steps/s^2; 0 = instantaneous
    double start = 0;
    double alarm_at_fraction = -1;
    bool moving = false, alarm = false, home_end = false, homing = false;
    int alarm_code = 0;
  };

  void Serve();
  void Handle(const uint8_t* query, int length);
  void Reply(const uint8_t* query, int length, bool corrupt);
  void AfterWrite(int address, int count);
  void Advance();  // integrates motion up to now
  void StartMove(double target, double speed, double acceleration);
  void PublishState();  // writes status/alarm/position into the register map
  int32_t Get(int address) const;
  void Set(int address, int32_t value);

  rig::DriveProfile profile_;
  DriveServerOptions options_;
  modbus_t* ctx_ = nullptr;
  modbus_mapping_t* map_ = nullptr;
  int listen_fd_ = -1;
  static constexpr std::size_t kMaxTcpClients = 8;
  std::vector<int> clients_;  // TCP connections
  int client_fd_ = -1;        // the connection (or pty) of the request being answered
  int pty_master_ = -1, pty_slave_ = -1;
  int port_ = 0;
  std::string pty_;

  mutable std::mutex mutex_;  // guards everything below (Serve runs on thread_)
  DriveFaults faults_;
  DriveServerCounters counters_;
  Motion motion_;
  std::chrono::steady_clock::time_point last_update_;

  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace brdfrig::sim
