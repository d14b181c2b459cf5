#include "sim/modbus_drive_server.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <modbus/modbus.h>
#include <netinet/in.h>
#include <poll.h>
#include <pty.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <vector>

#include "common/error.h"

namespace brdfrig::sim {
namespace {

constexpr int kFunctionWriteSingleRegister = 0x06;
constexpr int kFunctionWriteMultipleRegisters = 0x10;

std::string SystemError(const std::string& what) { return what + ": " + std::strerror(errno); }

}  // namespace

ModbusDriveServer::ModbusDriveServer(rig::DriveProfile profile, DriveServerOptions options)
    : profile_(std::move(profile)), options_(options) {
  map_ = modbus_mapping_new(16, 0, profile_.HighestRegister() + 1, 0);
  if (map_ == nullptr) throw Error(SystemError("simulated drive: register map"));
  motion_.position = motion_.target = options_.initial_position_steps;

  if (options_.transport == DriveServerOptions::Transport::kTcp) {
    ctx_ = modbus_new_tcp("127.0.0.1", options_.tcp_port);
    if (ctx_ == nullptr) throw Error(SystemError("simulated drive: modbus_new_tcp"));
    listen_fd_ = modbus_tcp_listen(ctx_, 1);
    if (listen_fd_ == -1) {
      const std::string message = SystemError("simulated drive: cannot listen on port " +
                                              std::to_string(options_.tcp_port));
      modbus_free(ctx_);
      modbus_mapping_free(map_);
      throw Error(message);
    }
    sockaddr_in address{};
    socklen_t length = sizeof(address);
    getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&address), &length);
    port_ = ntohs(address.sin_port);
  } else {
    char name[256] = {};
    if (openpty(&pty_master_, &pty_slave_, name, nullptr, nullptr) == -1) {
      modbus_mapping_free(map_);
      throw Error(SystemError("simulated drive: openpty"));
    }
    pty_ = name;
    // Raw mode on the line before any client opens it, and the slave end stays open here so
    // the master never reads EIO between client connections (RTU clients reopen the port).
    termios tios{};
    tcgetattr(pty_slave_, &tios);
    cfmakeraw(&tios);
    tcsetattr(pty_slave_, TCSANOW, &tios);
    // The RTU context serves the master end directly; it is never "connected" (that would
    // try to configure a serial port) and never closed through libmodbus.
    ctx_ = modbus_new_rtu(pty_.c_str(), 115200, 'N', 8, 1);
    if (ctx_ == nullptr) throw Error(SystemError("simulated drive: modbus_new_rtu"));
    modbus_set_socket(ctx_, pty_master_);
  }
  modbus_set_slave(ctx_, options_.slave);
  last_update_ = std::chrono::steady_clock::now();
  thread_ = std::thread([this] { Serve(); });
}

ModbusDriveServer::~ModbusDriveServer() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
  for (int fd : clients_) close(fd);
  if (listen_fd_ != -1) close(listen_fd_);
  if (pty_master_ != -1) close(pty_master_);
  if (pty_slave_ != -1) close(pty_slave_);
  modbus_free(ctx_);
  modbus_mapping_free(map_);
}

std::string ModbusDriveServer::Endpoint() const {
  if (options_.transport == DriveServerOptions::Transport::kTcp) {
    return "tcp://127.0.0.1:" + std::to_string(port_);
  }
  return "rtu:" + pty_;
}

void ModbusDriveServer::InjectFaults(const DriveFaults& faults) {
  std::lock_guard lock(mutex_);
  faults_ = faults;
}

DriveServerCounters ModbusDriveServer::counters() const {
  std::lock_guard lock(mutex_);
  return counters_;
}

int32_t ModbusDriveServer::position_steps() const {
  std::lock_guard lock(mutex_);
  return static_cast<int32_t>(std::lround(motion_.position));
}

bool ModbusDriveServer::moving() {
  std::lock_guard lock(mutex_);
  Advance();
  return motion_.moving;
}

bool ModbusDriveServer::alarm() const {
  std::lock_guard lock(mutex_);
  return motion_.alarm;
}

bool ModbusDriveServer::coil(int address) const {
  std::lock_guard lock(mutex_);
  return address >= 0 && address < map_->nb_bits && map_->tab_bits[address] != 0;
}

int32_t ModbusDriveServer::Get(int address) const {
  return rig::UnpackValue(profile_, &map_->tab_registers[address]);
}

void ModbusDriveServer::Set(int address, int32_t value) {
  rig::PackValue(profile_, value, &map_->tab_registers[address]);
}

void ModbusDriveServer::Serve() {
  uint8_t query[MODBUS_TCP_MAX_ADU_LENGTH];
  const bool tcp = options_.transport == DriveServerOptions::Transport::kTcp;
  while (!stop_) {
    std::vector<pollfd> fds;
    if (tcp) {
      fds.push_back({listen_fd_, POLLIN, 0});
      for (int fd : clients_) fds.push_back({fd, POLLIN, 0});
    } else {
      fds.push_back({pty_master_, POLLIN, 0});
    }
    // Short poll so that the destructor's stop flag is seen quickly.
    if (poll(fds.data(), static_cast<nfds_t>(fds.size()), 20) <= 0) continue;
    if (tcp && (fds[0].revents & POLLIN)) {
      const int fd = accept(listen_fd_, nullptr, nullptr);
      if (fd != -1) {
        clients_.push_back(fd);
        if (clients_.size() > kMaxTcpClients) {  // the oldest is most likely abandoned
          close(clients_.front());
          clients_.erase(clients_.begin());
        }
        std::lock_guard lock(mutex_);
        ++counters_.connections;
      }
      continue;
    }
    for (std::size_t i = tcp ? 1 : 0; i < fds.size(); ++i) {
      if (!(fds[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      client_fd_ = fds[i].fd;  // the connection being answered
      modbus_set_socket(ctx_, client_fd_);
      const int length = modbus_receive(ctx_, query);
      if (length == -1) {
        if (tcp) {  // the client went away (or sent garbage): forget this connection
          close(client_fd_);
          clients_.erase(std::find(clients_.begin(), clients_.end(), client_fd_));
        } else {
          modbus_flush(ctx_);
        }
        continue;
      }
      if (length > 0) Handle(query, length);
    }
  }
}

void ModbusDriveServer::Handle(const uint8_t* query, int length) {
  std::lock_guard lock(mutex_);
  ++counters_.requests;
  Advance();
  PublishState();
  if (faults_.drop_responses > 0) {
    --faults_.drop_responses;
    ++counters_.dropped;
    return;
  }
  if (faults_.exception_responses > 0) {
    --faults_.exception_responses;
    ++counters_.exceptions;
    modbus_reply_exception(ctx_, query, static_cast<unsigned>(faults_.exception_code));
    return;
  }
  const bool corrupt = faults_.corrupt_responses > 0;
  if (corrupt) {
    --faults_.corrupt_responses;
    ++counters_.corrupted;
  }
  Reply(query, length, corrupt);
  const int header = modbus_get_header_length(ctx_);
  const int function = query[header];
  const int address = (query[header + 1] << 8) | query[header + 2];
  if (function == kFunctionWriteMultipleRegisters) {
    AfterWrite(address, (query[header + 3] << 8) | query[header + 4]);
  } else if (function == kFunctionWriteSingleRegister) {
    AfterWrite(address, 1);
  }
}

void ModbusDriveServer::Reply(const uint8_t* query, int length, bool corrupt) {
  if (!corrupt) {
    modbus_reply(ctx_, query, length, map_);
    return;
  }
  // Let libmodbus build the correct answer into a socket pair, then damage it on the way out:
  // the last CRC byte for RTU, the transaction id for TCP (both make the client reject it).
  int pair[2];
  if (socketpair(AF_UNIX, SOCK_STREAM, 0, pair) == -1) return;
  const int real =
      options_.transport == DriveServerOptions::Transport::kTcp ? client_fd_ : pty_master_;
  modbus_set_socket(ctx_, pair[0]);
  modbus_reply(ctx_, query, length, map_);
  modbus_set_socket(ctx_, real);
  uint8_t frame[MODBUS_TCP_MAX_ADU_LENGTH];
  const ssize_t n = recv(pair[1], frame, sizeof(frame), MSG_DONTWAIT);
  close(pair[0]);
  close(pair[1]);
  if (n <= 0) return;
  if (options_.transport == DriveServerOptions::Transport::kTcp) {
    frame[0] ^= 0x5A;
  } else {
    frame[n - 1] ^= 0x5A;
  }
  const ssize_t written = write(real, frame, static_cast<std::size_t>(n));
  (void)written;  // a client that has gone away will notice on its own
}

void ModbusDriveServer::AfterWrite(int address, int count) {
  auto touches = [&](int reg) { return address <= reg + 1 && reg < address + count; };
  if (touches(profile_.trigger.address) &&
      Get(profile_.trigger.address) == profile_.trigger.value) {
    Set(profile_.trigger.address, 0);  // the drive consumes the trigger
    const int accel_reg = profile_.acceleration;
    StartMove(Get(profile_.position), Get(profile_.speed), Get(accel_reg));
    ++counters_.moves;
  }
  if (touches(profile_.command)) {
    const auto command = static_cast<uint32_t>(Get(profile_.command));
    if (command & (1u << profile_.stop_bit)) {
      // Immediate stop: the simulation does not model the deceleration ramp of a stop.
      ++counters_.stops;
      motion_.moving = false;
      motion_.velocity = 0;
      motion_.target = motion_.position;
    }
    if ((command & (1u << profile_.home_bit)) && !motion_.alarm) {
      ++counters_.homes;
      const double speed = Get(profile_.speed) > 0 ? Get(profile_.speed) : 1000;
      StartMove(0, speed, Get(profile_.acceleration));
      motion_.homing = true;
    }
    if ((command & (1u << profile_.alarm_reset_bit)) && motion_.alarm) {
      ++counters_.alarm_resets;
      motion_.alarm = false;
      motion_.alarm_code = 0;
    }
  }
  PublishState();
}

void ModbusDriveServer::StartMove(double target, double speed, double acceleration) {
  if (motion_.alarm) return;  // a drive in alarm ignores operation commands
  motion_.target = target;
  motion_.speed = std::max(1.0, speed * faults_.speed_factor);
  motion_.acceleration = acceleration;
  motion_.start = motion_.position;
  motion_.alarm_at_fraction = faults_.alarm_at_fraction;
  faults_.alarm_at_fraction = -1;
  motion_.moving = std::abs(target - motion_.position) > 0.5;
  motion_.homing = false;
  if (!motion_.moving) motion_.position = target;
}

void ModbusDriveServer::Advance() {
  const auto now = std::chrono::steady_clock::now();
  double elapsed = std::chrono::duration<double>(now - last_update_).count();
  last_update_ = now;
  Motion& m = motion_;
  // Fixed 1 ms steps: a trapezoid (accelerate, cruise, brake in time to stop at the target).
  constexpr double kStep = 1e-3;
  while (m.moving && elapsed > 0) {
    const double dt = std::min(kStep, elapsed);
    elapsed -= dt;
    const double remaining = m.target - m.position;
    const double direction = remaining > 0 ? 1 : -1;
    const double a = m.acceleration > 0 ? m.acceleration : 1e12;
    const double braking = m.velocity * m.velocity / (2 * a);
    double speed = std::abs(m.velocity);
    speed = std::abs(remaining) <= braking ? std::max(0.0, speed - a * dt)
                                           : std::min(m.speed, speed + a * dt);
    speed = std::max(speed, std::min(m.speed, 50.0));  // creep so a move always ends
    m.velocity = direction * speed;
    const double step = m.velocity * dt;
    if (std::abs(step) >= std::abs(remaining)) {
      m.position = m.target;
      m.velocity = 0;
      m.moving = false;
      if (m.homing) m.home_end = true;
      m.homing = false;
    } else {
      m.position += step;
    }
    const double travel = std::abs(m.target - m.start);
    if (m.alarm_at_fraction >= 0 && travel > 0 &&
        std::abs(m.position - m.start) >= m.alarm_at_fraction * travel) {
      m.alarm = true;
      m.alarm_code = faults_.alarm_code;
      m.alarm_at_fraction = -1;
      m.moving = false;
      m.velocity = 0;
    }
  }
}

void ModbusDriveServer::PublishState() {
  const Motion& m = motion_;
  const bool in_position = !m.moving && std::abs(m.position - m.target) < 1;
  uint32_t status = 0;
  auto put = [&status](int bit, bool on) {
    if (on) status |= 1u << bit;
  };
  put(profile_.ready_bit, !m.moving && !m.alarm);
  put(profile_.moving_bit, m.moving);
  put(profile_.in_position_bit, in_position);
  put(profile_.alarm_bit, m.alarm);
  if (profile_.home_end_bit) put(*profile_.home_end_bit, m.home_end);
  Set(profile_.status, static_cast<int32_t>(status));
  Set(profile_.alarm_code, m.alarm ? m.alarm_code : 0);
  Set(profile_.position_readback, static_cast<int32_t>(std::lround(m.position)));
}

}  // namespace brdfrig::sim
