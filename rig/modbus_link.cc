#include "rig/modbus_link.h"

#include <modbus/modbus.h>

#include <cerrno>
#include <cstring>
#include <map>
#include <thread>

namespace brdfrig::rig {
namespace {

bool IsException(int err) { return err >= EMBXILFUN && err <= EMBXGTAR; }

bool IsBadFrame(int err) {
  return err == EMBBADCRC || err == EMBBADDATA || err == EMBBADEXC || err == EMBMDATA ||
         err == EMBBADSLAVE || err == EMBUNKEXC;
}

std::string Describe(int err) {
  std::string text = modbus_strerror(err);
  if (err == ETIMEDOUT) {
    text += " (no answer: check power, cabling, slave id and, for RTU, baud rate and parity)";
  } else if (err == EMBBADCRC) {
    text += " (corrupted frame: check termination, grounding and baud rate)";
  }
  return text;
}

}  // namespace

std::string ModbusLinkOptions::Endpoint() const {
  if (transport == Transport::kTcp) return "tcp://" + host + ":" + std::to_string(port);
  return "rtu:" + device + "@" + std::to_string(baud) + "," + std::to_string(data_bits) + parity +
         std::to_string(stop_bits);
}

void ModbusLinkOptions::Validate() const {
  if (transport == Transport::kTcp) {
    if (host.empty()) throw OptionsError("modbus: host is empty");
    if (port <= 0 || port > 65535) throw OptionsError("modbus: port must be 1..65535");
  } else {
    if (device.empty()) throw OptionsError("modbus: RTU needs a serial device");
    if (parity != 'N' && parity != 'E' && parity != 'O') {
      throw OptionsError("modbus: parity must be N, E or O");
    }
    if (data_bits < 5 || data_bits > 8) throw OptionsError("modbus: data_bits must be 5..8");
    if (stop_bits != 1 && stop_bits != 2) throw OptionsError("modbus: stop_bits must be 1 or 2");
  }
  if (response_timeout.count() <= 0) throw OptionsError("modbus: timeout must be positive");
  if (attempts < 1) throw OptionsError("modbus: attempts must be at least 1");
}

ModbusLinkOptions ReadModbusLinkOptions(const YamlNode& settings) {
  ModbusLinkOptions o;
  const YamlNode transport = settings.Required("transport");
  const std::string kind = transport.AsString();
  if (kind == "tcp") {
    o.transport = ModbusLinkOptions::Transport::kTcp;
    o.host = settings.Required("host").AsString();
    if (const auto port = settings.Optional("port")) {
      o.port = static_cast<int>(port->InRange(port->AsInt(), 1, 65535));
    }
  } else if (kind == "rtu") {
    o.transport = ModbusLinkOptions::Transport::kRtu;
    o.device = settings.Required("device").AsString();
    if (const auto baud = settings.Optional("baud")) o.baud = baud->AsInt();
    if (const auto parity = settings.Optional("parity")) {
      const std::string p = parity->AsString();
      if (p == "N" || p == "none") {
        o.parity = 'N';
      } else if (p == "E" || p == "even") {
        o.parity = 'E';
      } else if (p == "O" || p == "odd") {
        o.parity = 'O';
      } else {
        parity->Fail("expected none, even or odd, got '" + p + "'");
      }
    }
    if (const auto bits = settings.Optional("data_bits")) {
      o.data_bits = static_cast<int>(bits->InRange(bits->AsInt(), 5, 8));
    }
    if (const auto bits = settings.Optional("stop_bits")) {
      o.stop_bits = static_cast<int>(bits->InRange(bits->AsInt(), 1, 2));
    }
  } else {
    transport.Fail("expected tcp or rtu, got '" + kind + "'");
  }
  if (const auto timeout = settings.Optional("timeout_ms")) {
    o.response_timeout =
        std::chrono::milliseconds(static_cast<int>(timeout->InRange(timeout->AsInt(), 1, 60000)));
  }
  if (const auto attempts = settings.Optional("attempts")) {
    o.attempts = static_cast<int>(attempts->InRange(attempts->AsInt(), 1, 20));
  }
  return o;
}

ModbusLink::ModbusLink(ModbusLinkOptions options) : options_(std::move(options)) {
  options_.Validate();
}

ModbusLink::~ModbusLink() { Disconnect(); }

ModbusLinkStats ModbusLink::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

void ModbusLink::Connect() {
  if (options_.transport == ModbusLinkOptions::Transport::kTcp) {
    ctx_ = modbus_new_tcp(options_.host.c_str(), options_.port);
  } else {
    ctx_ = modbus_new_rtu(options_.device.c_str(), options_.baud, options_.parity,
                          options_.data_bits, options_.stop_bits);
  }
  if (ctx_ == nullptr) {
    throw ModbusError(ModbusError::Kind::kConnect, 0,
                      "modbus: bad endpoint " + options_.Endpoint() + ": " + std::strerror(errno));
  }
  // We decide when to reconnect and retry; libmodbus must not sleep or reconnect on its own.
  modbus_set_error_recovery(ctx_, MODBUS_ERROR_RECOVERY_NONE);
  const auto ms = options_.response_timeout.count();
  modbus_set_response_timeout(ctx_, static_cast<uint32_t>(ms / 1000),
                              static_cast<uint32_t>((ms % 1000) * 1000));
  modbus_set_byte_timeout(ctx_, static_cast<uint32_t>(ms / 1000),
                          static_cast<uint32_t>((ms % 1000) * 1000));
  if (modbus_connect(ctx_) == -1) {
    const int err = errno;
    modbus_free(ctx_);
    ctx_ = nullptr;
    throw ModbusError(ModbusError::Kind::kConnect, 0,
                      "modbus: cannot connect to " + options_.Endpoint() + ": " +
                          modbus_strerror(err) +
                          (options_.transport == ModbusLinkOptions::Transport::kTcp
                               ? " (is the drive or gateway powered and reachable?)"
                               : " (does the serial device exist, and may this user open it?)"));
  }
  if (connected_once_) ++stats_.reconnects;
  connected_once_ = true;
}

void ModbusLink::Disconnect() {
  if (ctx_ == nullptr) return;
  modbus_close(ctx_);
  modbus_free(ctx_);
  ctx_ = nullptr;
}

template <typename Request>
void ModbusLink::Run(int slave, const char* what, int address, Request request) {
  std::lock_guard lock(mutex_);
  ++stats_.requests;
  auto backoff = options_.retry_backoff;
  ModbusError last(ModbusError::Kind::kOther, 0, "");
  for (int attempt = 1; attempt <= options_.attempts; ++attempt) {
    if (attempt > 1) {
      ++stats_.retries;
      std::this_thread::sleep_for(backoff);
      backoff *= 2;
    }
    const std::string where = std::string("modbus: ") + what + " at register " +
                              std::to_string(address) + " of slave " + std::to_string(slave) +
                              " on " + options_.Endpoint();
    try {
      if (ctx_ == nullptr) Connect();
    } catch (const ModbusError& e) {
      last = e;
      continue;
    }
    modbus_set_slave(ctx_, slave);
    if (request(ctx_) != -1) return;
    const int err = errno;
    if (IsException(err)) {
      const int code = err - MODBUS_ENOBASE;
      last = ModbusError(ModbusError::Kind::kException, code,
                         where + ": the drive answered with exception " + std::to_string(code) +
                             " (" + modbus_strerror(err) + ")");
      // Busy and acknowledge mean "ask again later"; other exceptions will not change.
      if (code == MODBUS_EXCEPTION_SLAVE_OR_SERVER_BUSY || code == MODBUS_EXCEPTION_ACKNOWLEDGE) {
        continue;
      }
      throw last;
    }
    const ModbusError::Kind kind = err == ETIMEDOUT  ? ModbusError::Kind::kTimeout
                                   : IsBadFrame(err) ? ModbusError::Kind::kBadFrame
                                                     : ModbusError::Kind::kConnect;
    last = ModbusError(kind, 0, where + ": " + Describe(err));
    // A late or partial answer may still arrive: start the next attempt on a fresh connection.
    Disconnect();
  }
  throw ModbusError(last.kind(), last.exception_code(),
                    std::string(last.what()) + " (after " + std::to_string(options_.attempts) +
                        (options_.attempts == 1 ? " attempt)" : " attempts)"));
}

std::vector<uint16_t> ModbusLink::ReadRegisters(int slave, int address, int count) {
  std::vector<uint16_t> out(static_cast<std::size_t>(count));
  Run(slave, "read", address, [&](modbus_t* ctx) {
    return modbus_read_registers(ctx, address, count, out.data()) == count ? 0 : -1;
  });
  return out;
}

void ModbusLink::WriteRegisters(int slave, int address, const std::vector<uint16_t>& values) {
  const int n = static_cast<int>(values.size());
  Run(slave, "write", address, [&](modbus_t* ctx) {
    return modbus_write_registers(ctx, address, n, values.data()) == n ? 0 : -1;
  });
}

void ModbusLink::WriteCoil(int slave, int address, bool on) {
  Run(slave, "write coil", address,
      [&](modbus_t* ctx) { return modbus_write_bit(ctx, address, on ? 1 : 0) == 1 ? 0 : -1; });
}

bool ModbusLink::ReadCoil(int slave, int address) {
  uint8_t bit = 0;
  Run(slave, "read coil", address,
      [&](modbus_t* ctx) { return modbus_read_bits(ctx, address, 1, &bit) == 1 ? 0 : -1; });
  return bit != 0;
}

std::shared_ptr<ModbusLink> SharedModbusLink(const ModbusLinkOptions& options) {
  static std::mutex mutex;
  static std::map<std::string, std::weak_ptr<ModbusLink>> links;
  std::lock_guard lock(mutex);
  std::weak_ptr<ModbusLink>& slot = links[options.Endpoint()];
  if (auto link = slot.lock()) {
    // Devices on one bus share its timing: silently keeping the first device's would hide a
    // setting the second one asks for.
    const ModbusLinkOptions& used = link->options();
    if (used.response_timeout != options.response_timeout || used.attempts != options.attempts ||
        used.retry_backoff != options.retry_backoff) {
      throw OptionsError("modbus: devices on " + options.Endpoint() +
                         " share one link but ask for different timeout_ms/attempts: give "
                         "them the same values");
    }
    return link;
  }
  auto link = std::make_shared<ModbusLink>(options);
  slot = link;
  return link;
}

}  // namespace brdfrig::rig
