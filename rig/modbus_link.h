// One Modbus connection (TCP, or RTU on a serial line) owned by us rather than by libmodbus:
// libmodbus's own error recovery is off (MODBUS_ERROR_RECOVERY_NONE), so a timeout or a
// corrupted frame comes back to this class, which reconnects (a half-read frame must not be
// mistaken for the next answer) and retries a bounded number of times. Every request has an
// explicit response timeout. Several devices on one bus (RS-485 drives with different slave
// ids) share one link through SharedModbusLink; requests are serialized by a mutex.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "common/error.h"
#include "common/yaml_reader.h"

typedef struct _modbus modbus_t;

namespace brdfrig::rig {

struct ModbusLinkOptions {
  enum class Transport { kTcp, kRtu };
  Transport transport = Transport::kTcp;
  std::string host = "127.0.0.1";  // TCP
  int port = 502;                  // TCP
  std::string device;              // RTU: e.g. /dev/ttyUSB0 (or a pty for the simulator)
  int baud = 115200;               // RTU
  char parity = 'E';               // RTU: 'N', 'E' or 'O' (AZ drives default to even)
  int data_bits = 8;               // RTU
  int stop_bits = 1;               // RTU
  std::chrono::milliseconds response_timeout{500};
  int attempts = 3;  // per request, including the first; timeouts and bad frames are retried
  std::chrono::milliseconds retry_backoff{20};  // doubled after every failed attempt

  // "tcp://host:port" or "rtu:/dev/ttyUSB0@115200,8E1": for messages and link sharing.
  std::string Endpoint() const;
  void Validate() const;  // throws OptionsError
};

// Reads the transport keys of a device's rig.yaml settings (transport, host, port, device,
// baud, parity, data_bits, stop_bits, timeout_ms, attempts); other keys are left for the caller.
ModbusLinkOptions ReadModbusLinkOptions(const YamlNode& settings);

class ModbusError : public Error {
 public:
  enum class Kind { kConnect, kTimeout, kBadFrame, kException, kOther };
  ModbusError(Kind kind, int exception_code, const std::string& message)
      : Error(message), kind_(kind), exception_code_(exception_code) {}
  Kind kind() const { return kind_; }
  int exception_code() const { return exception_code_; }  // Modbus exception, 0 if none

 private:
  Kind kind_;
  int exception_code_;
};

struct ModbusLinkStats {
  int requests = 0;
  int retries = 0;     // attempts after the first
  int reconnects = 0;  // connections opened after the first
};

class ModbusLink {
 public:
  explicit ModbusLink(ModbusLinkOptions options);
  ~ModbusLink();
  ModbusLink(const ModbusLink&) = delete;
  ModbusLink& operator=(const ModbusLink&) = delete;

  std::vector<uint16_t> ReadRegisters(int slave, int address, int count);
  void WriteRegisters(int slave, int address, const std::vector<uint16_t>& values);
  void WriteCoil(int slave, int address, bool on);
  bool ReadCoil(int slave, int address);

  const ModbusLinkOptions& options() const { return options_; }
  ModbusLinkStats stats() const;

 private:
  // Runs `request` (a libmodbus call returning -1 on failure) with reconnects and retries.
  template <typename Request>
  void Run(int slave, const char* what, int address, Request request);
  void Connect();
  void Disconnect();

  ModbusLinkOptions options_;
  mutable std::mutex mutex_;
  modbus_t* ctx_ = nullptr;
  bool connected_once_ = false;
  ModbusLinkStats stats_;
};

// The link for an endpoint, shared by every device that names the same endpoint while any of
// them is alive (one serial port cannot be opened twice; one TCP gateway serves many slaves).
std::shared_ptr<ModbusLink> SharedModbusLink(const ModbusLinkOptions& options);

}  // namespace brdfrig::rig
