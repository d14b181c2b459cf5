#include "simcamera/ptpip_server.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "common/error.h"
#include "simcamera/ptp_codes.h"

namespace brdfrig::simcamera {
namespace {

constexpr std::chrono::milliseconds kPacketTimeout{5000};
const std::vector<std::uint8_t> kCameraGuid = {0x62, 0x72, 0x64, 0x66, 0x72, 0x69, 0x67, 0x00,
                                               0x73, 0x69, 0x6d, 0x63, 0x61, 0x6d, 0x00, 0x01};

void CloseFd(int& fd) {
  if (fd >= 0) close(fd);
  fd = -1;
}

bool Readable(int fd) {
  pollfd p{fd, POLLIN, 0};
  return poll(&p, 1, 0) > 0 && (p.revents & (POLLIN | POLLHUP | POLLERR));
}

// Operations that a body busy writing its card refuses.
bool RefusedWhenBusy(std::uint16_t code) {
  return code == op::kGetObject || code == op::kDeleteObject;
}

}  // namespace

PtpIpCameraServer::PtpIpCameraServer(CameraServerOptions options, ShotFunction shoot)
    : options_(std::move(options)), responder_(options_.offer, std::move(shoot)) {
  port_ = options_.port;
  Listen();
  thread_ = std::thread([this] { Serve(); });
}

PtpIpCameraServer::~PtpIpCameraServer() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
  CloseConnection();
  CloseFd(listener_);
}

std::string PtpIpCameraServer::PortPath() const {
  // libgphoto2 connects the event channel to 15740 unless the path names its port too
  // ("ptpip:HOST:PORT:EVENTPORT"; checked with 2.5.30), whatever the command port is.
  const std::string port = std::to_string(port_);
  return "ptpip:" + options_.host + ":" + port + (port_ == 15740 ? "" : ":" + port);
}

void PtpIpCameraServer::Listen() {
  listener_ = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (listener_ < 0) throw Error(std::string("simulated camera: socket(): ") + strerror(errno));
  const int on = 1;
  setsockopt(listener_, SOL_SOCKET, SO_REUSEADDR, &on, sizeof on);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port_));
  if (inet_pton(AF_INET, options_.host.c_str(), &address.sin_addr) != 1) {
    CloseFd(listener_);
    throw Error("simulated camera: '" + options_.host + "' is not an IPv4 address");
  }
  if (bind(listener_, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0 ||
      listen(listener_, 4) != 0) {
    const std::string why = strerror(errno);
    CloseFd(listener_);
    throw Error("simulated camera: cannot listen on " + options_.host + ":" +
                std::to_string(port_) + ": " + why);
  }
  socklen_t length = sizeof address;
  getsockname(listener_, reinterpret_cast<sockaddr*>(&address), &length);
  port_ = ntohs(address.sin_port);
}

void PtpIpCameraServer::InjectFaults(const CameraFaults& faults) {
  std::lock_guard lock(mutex_);
  faults_ = faults;
  responder_.store().set_capacity_files(faults.card_capacity_files);
}

CameraServerCounters PtpIpCameraServer::counters() const {
  std::lock_guard lock(mutex_);
  return counters_;
}

ExposureSettings PtpIpCameraServer::exposure() const {
  std::lock_guard lock(mutex_);
  return responder_.exposure();
}

std::size_t PtpIpCameraServer::files_on_card() const {
  std::lock_guard lock(mutex_);
  return responder_.store().files();
}

void PtpIpCameraServer::CloseConnection() {
  CloseFd(command_);
  CloseFd(event_);
}

void PtpIpCameraServer::Serve() {
  while (!stop_) {
    if (vanished_) {
      if (std::chrono::steady_clock::now() < back_at_) {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        continue;
      }
      try {
        Listen();
        vanished_ = false;
      } catch (const Error& e) {
        std::fprintf(stderr, "%s; retrying\n", e.what());
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
        continue;
      }
    }
    pollfd fds[3] = {{listener_, POLLIN, 0}, {command_, POLLIN, 0}, {event_, POLLIN, 0}};
    if (poll(fds, 3, 50) <= 0) continue;
    try {
      if (fds[0].revents & POLLIN) Accept();
      if (command_ >= 0 && (fds[1].revents & (POLLIN | POLLHUP | POLLERR))) ServeCommand();
      // On the event channel the initiator only probes whether the camera is alive (Probe
      // Request → Probe Response); otherwise readable means the connection is closing.
      if (event_ >= 0 && Readable(event_)) {
        const std::optional<Packet> packet = ReadPacket(event_, kPacketTimeout);
        if (!packet) {
          CloseFd(event_);
        } else if (packet->type == PacketType::kProbeRequest) {
          WritePacket(event_, PacketType::kProbeResponse, {});
        }
      }
    } catch (const Error& e) {
      // A protocol error ends the connection, as a body drops a confused initiator.
      std::fprintf(stderr, "simulated camera: %s; closing the connection\n", e.what());
      CloseConnection();
    }
  }
}

void PtpIpCameraServer::Accept() {
  int fd = accept4(listener_, nullptr, nullptr, SOCK_CLOEXEC);
  if (fd < 0) return;
  const int on = 1;
  setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);
  // A bad newcomer costs only its own connection, never the initiator already served.
  std::optional<Packet> init;
  try {
    init = ReadPacket(fd, kPacketTimeout);
  } catch (const Error& e) {
    std::fprintf(stderr, "simulated camera: %s; refusing the new connection\n", e.what());
  }
  if (!init) {
    close(fd);
    return;
  }
  if (init->type == PacketType::kInitCommandRequest) {
    ParseInitCommandRequest(*init);  // any initiator is welcome; the GUID is not checked
    CloseConnection();
    command_ = fd;
    {
      std::lock_guard lock(mutex_);
      responder_.ResetSession();
      ++counters_.connections;
    }
    WritePacket(command_, PacketType::kInitCommandAck,
                InitCommandAckPayload(1, kCameraGuid, options_.offer.model));
  } else if (init->type == PacketType::kInitEventRequest && command_ >= 0) {
    CloseFd(event_);
    event_ = fd;
    WritePacket(event_, PacketType::kInitEventAck, {});
  } else {
    WritePacket(fd, PacketType::kInitFail, {1, 0, 0, 0});
    close(fd);
  }
}

void PtpIpCameraServer::SendEvents(const std::vector<PtpEvent>& events, std::uint32_t transaction) {
  for (const PtpEvent& e : events) {
    if (event_ < 0) return;
    if (!WritePacket(event_, PacketType::kEvent, EventPayload(e.code, transaction, e.params))) {
      CloseFd(event_);
    }
  }
}

void PtpIpCameraServer::ServeCommand() {
  const std::optional<Packet> packet = ReadPacket(command_, kPacketTimeout);
  if (!packet) {
    CloseConnection();  // the initiator went away
    return;
  }
  if (packet->type == PacketType::kProbeRequest) {
    WritePacket(command_, PacketType::kProbeResponse, {});
    return;
  }
  if (packet->type != PacketType::kOperationRequest) {
    throw Error("unexpected packet type " +
                std::to_string(static_cast<std::uint32_t>(packet->type)) +
                " on the command connection");
  }
  const OperationRequest request = ParseOperationRequest(*packet);
  std::vector<std::uint8_t> data;
  if (request.data_phase == kDataPhaseToCamera) {
    data = ReadDataPhase(command_, request.transaction, kPacketTimeout);
  }

  PtpReply reply;
  double delay_s = 0;
  bool drop = false;
  {
    std::lock_guard lock(mutex_);
    ++counters_.operations;
    delay_s = faults_.response_delay_s;
    if (request.code == op::kInitiateCapture && faults_.vanish_s > 0) {
      back_at_ = std::chrono::steady_clock::now() +
                 std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                     std::chrono::duration<double>(faults_.vanish_s));
      faults_.vanish_s = 0;
      ++counters_.vanished;
      vanished_ = true;
    } else if (RefusedWhenBusy(request.code) && faults_.busy_responses > 0) {
      --faults_.busy_responses;
      ++counters_.busy;
      reply.code = rc::kDeviceBusy;
    } else if (request.code == op::kSetDevicePropValue && faults_.busy_settings > 0) {
      --faults_.busy_settings;
      ++counters_.busy;
      reply.code = rc::kDeviceBusy;
    } else {
      reply = responder_.Handle(request, data);
      if (request.code == op::kInitiateCapture) {
        if (reply.code == rc::kStoreFull) ++counters_.store_full;
        if (reply.code == rc::kOk) ++counters_.captures;
      }
      if (request.code == op::kGetObject && reply.data && faults_.drop_downloads > 0) {
        --faults_.drop_downloads;
        ++counters_.dropped;
        drop = true;
      }
    }
  }
  if (vanished_) {
    CloseConnection();
    CloseFd(listener_);
    return;
  }
  if (delay_s > 0) std::this_thread::sleep_for(std::chrono::duration<double>(delay_s));
  if (drop) {
    // Start data announces the file, then the link dies: the initiator sees a broken stream.
    std::vector<std::uint8_t> start = {0, 0, 0, 0};
    for (int i = 0; i < 4; ++i)
      start[i] = static_cast<std::uint8_t>(request.transaction >> (8 * i));
    const std::uint64_t size = reply.data->size();
    for (int i = 0; i < 8; ++i) start.push_back(static_cast<std::uint8_t>(size >> (8 * i)));
    WritePacket(command_, PacketType::kStartData, start);
    CloseConnection();
    return;
  }
  if (reply.data && !WriteDataPhase(command_, request.transaction, *reply.data)) {
    CloseConnection();
    return;
  }
  if (!WritePacket(command_, PacketType::kOperationResponse,
                   ResponsePayload(reply.code, request.transaction, reply.params))) {
    CloseConnection();
    return;
  }
  if (reply.after) {
    std::vector<PtpEvent> events;
    {
      std::lock_guard lock(mutex_);
      events = reply.after();
    }
    SendEvents(events, request.transaction);
  }
}

}  // namespace brdfrig::simcamera
