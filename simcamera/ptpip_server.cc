#include "simcamera/ptpip_server.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "common/error.h"
#include "simcamera/ptp_codes.h"
#include "simcamera/ptp_data.h"

namespace brdfrig::simcamera {
namespace {

// How often the loop wakes without traffic: the resolution of the deadlines and of stopping.
constexpr int kPollMs = 20;
// After accept() ran out of descriptors the listener rests this long instead of spinning.
constexpr std::chrono::milliseconds kAcceptPause{100};
// Connections accepted per loop at most, so that a flood does not starve the served ones.
constexpr int kAcceptsPerLoop = 32;
const std::vector<std::uint8_t> kCameraGuid = {0x62, 0x72, 0x64, 0x66, 0x72, 0x69, 0x67, 0x00,
                                               0x73, 0x69, 0x6d, 0x63, 0x61, 0x6d, 0x00, 0x01};

// Operations that a body busy writing its card refuses.
bool RefusedWhenBusy(std::uint16_t code) {
  return code == op::kGetObject || code == op::kDeleteObject;
}

}  // namespace

PtpIpCameraServer::PtpIpCameraServer(CameraServerOptions options, ShotFunction shoot)
    : options_(std::move(options)), responder_(options_.offer, std::move(shoot)) {
  port_ = options_.port;
  responder_.store().set_capacity_bytes(options_.card_bytes);
  Listen();
  thread_ = std::thread([this] { Serve(); });
}

PtpIpCameraServer::~PtpIpCameraServer() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
  connections_.clear();
  if (listener_ >= 0) close(listener_);
}

std::string PtpIpCameraServer::PortPath() const {
  // libgphoto2 connects the event channel to 15740 unless the path names its port too
  // ("ptpip:HOST:PORT:EVENTPORT"; checked with 2.5.30), whatever the command port is.
  const std::string port = std::to_string(port_);
  return "ptpip:" + options_.host + ":" + port + (port_ == 15740 ? "" : ":" + port);
}

void PtpIpCameraServer::Listen() {
  listener_ = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (listener_ < 0) throw Error(std::string("simulated camera: socket(): ") + strerror(errno));
  const int on = 1;
  setsockopt(listener_, SOL_SOCKET, SO_REUSEADDR, &on, sizeof on);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port_));
  const auto fail = [this](const std::string& why) {
    close(listener_);
    listener_ = -1;
    throw Error(why);
  };
  if (inet_pton(AF_INET, options_.host.c_str(), &address.sin_addr) != 1) {
    fail("simulated camera: '" + options_.host + "' is not an IPv4 address");
  }
  if (bind(listener_, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0 ||
      listen(listener_, 128) != 0) {
    fail("simulated camera: cannot listen on " + options_.host + ":" + std::to_string(port_) +
         ": " + strerror(errno));
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

PtpIpConnection* PtpIpCameraServer::Find(ConnectionRole role) {
  for (const auto& c : connections_) {
    if (!c->closed && c->role == role) return c.get();
  }
  return nullptr;
}

void PtpIpCameraServer::Close(PtpIpConnection& c, const std::string& why) {
  if (c.closed) return;
  c.closed = true;
  if (!why.empty()) {
    std::fprintf(stderr, "simulated camera: %s; closing the %s\n", why.c_str(),
                 c.role == ConnectionRole::kNewcomer ? "new connection" : "connection");
    std::lock_guard lock(mutex_);
    ++counters_.refused;
  }
}

void PtpIpCameraServer::CloseAll() {
  for (const auto& c : connections_) c->closed = true;
}

void PtpIpCameraServer::Serve() {
  while (!stop_) {
    if (vanished_) {
      if (Clock::now() < back_at_) {
        std::this_thread::sleep_for(std::chrono::milliseconds(kPollMs));
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
    ServeOnce();
  }
}

void PtpIpCameraServer::ServeOnce() {
  Clock::time_point now = Clock::now();
  std::vector<pollfd> fds;
  fds.push_back({now < accept_paused_until_ ? -1 : listener_, POLLIN, 0});
  const std::size_t polled = connections_.size();
  for (const auto& c : connections_) {
    short events = 0;
    // A command connection reads its next request only once the reply to the last one has
    // gone: one reply at a time is all the memory a client can claim.
    const bool wants_input =
        !c->close_when_sent &&
        (c->role == ConnectionRole::kNewcomer ||
         (c->role == ConnectionRole::kCommand && c->unsent() == 0 && !c->after) ||
         (c->role == ConnectionRole::kEvent && c->unsent() == 0));
    if (wants_input) events |= POLLIN;
    if (c->ready_to_send(now)) events |= POLLOUT;
    fds.push_back({c->fd(), events, 0});
  }
  if (poll(fds.data(), fds.size(), kPollMs) < 0 && errno != EINTR) {
    std::this_thread::sleep_for(std::chrono::milliseconds(kPollMs));
  }
  now = Clock::now();
  if (fds[0].revents & POLLIN) Accept(now);
  for (std::size_t i = 0; i < polled && !vanished_; ++i) {
    PtpIpConnection& c = *connections_[i];
    const short revents = fds[i + 1].revents;
    if (c.closed || revents == 0) continue;
    try {
      if (revents & POLLOUT) {
        if (!c.Flush(now)) {
          Close(c, "");  // the peer went away
          continue;
        }
      }
      if ((fds[i + 1].events & POLLIN) && (revents & (POLLIN | POLLHUP | POLLERR))) {
        while (!c.closed && !c.peer_closed()) {
          std::optional<Packet> packet = c.Receive(now);
          if (!packet) break;
          OnPacket(c, std::move(*packet), now);
          if (vanished_ || c.unsent() > 0 || c.after) break;  // one request at a time
        }
        if (c.peer_closed()) Close(c, "");
      } else if (revents & (POLLHUP | POLLERR)) {
        Close(c, "");
      }
    } catch (const Error& e) {
      // A protocol error ends this connection, as a body drops a confused initiator; every
      // other connection goes on.
      Close(c, e.what());
    }
  }
  if (vanished_) {
    connections_.clear();
    close(listener_);
    listener_ = -1;
    return;
  }
  for (const auto& c : connections_) {
    if (c->closed) continue;
    if (c->ready_to_send(now) && !c->Flush(now)) {
      Close(*c, "");
      continue;
    }
    RunAfterWork(*c, now);
    CheckDeadlines(*c, now);
    if (c->close_when_sent && c->unsent() == 0) c->closed = true;
  }
  std::erase_if(connections_, [](const auto& c) { return c->closed; });
}

void PtpIpCameraServer::Accept(Clock::time_point now) {
  for (int i = 0; i < kAcceptsPerLoop; ++i) {
    const int fd = accept4(listener_, nullptr, nullptr, SOCK_CLOEXEC | SOCK_NONBLOCK);
    if (fd < 0) {
      if (errno == EMFILE || errno == ENFILE || errno == ENOBUFS || errno == ENOMEM) {
        // Out of descriptors: the pending connection stays in the backlog; without the pause
        // the readable listener would spin the loop.
        std::fprintf(stderr, "simulated camera: accept(): %s; pausing new connections\n",
                     strerror(errno));
        accept_paused_until_ = now + kAcceptPause;
      }
      return;
    }
    const int on = 1;
    setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);
    // Too many newcomers: the oldest makes room (a real initiator sends its init request at
    // once, so only the silent ones grow old).
    int newcomers = 0;
    for (const auto& c : connections_) {
      if (!c->closed && c->role == ConnectionRole::kNewcomer) ++newcomers;
    }
    if (newcomers >= options_.limits.max_newcomers) {
      for (const auto& c : connections_) {
        if (!c->closed && c->role == ConnectionRole::kNewcomer) {
          Close(*c, "too many connections without an init request");
          c->CloseSocket();
          break;
        }
      }
    }
    connections_.push_back(std::make_unique<PtpIpConnection>(fd, now));
  }
}

void PtpIpCameraServer::OnPacket(PtpIpConnection& c, Packet packet, Clock::time_point now) {
  switch (c.role) {
    case ConnectionRole::kNewcomer:
      OnNewcomer(c, packet, now);
      return;
    case ConnectionRole::kCommand:
      OnCommand(c, packet, now);
      return;
    case ConnectionRole::kEvent:
      // On the event channel the initiator only probes whether the camera is alive.
      if (packet.type == PacketType::kProbeRequest) {
        c.Queue(EncodePacket(PacketType::kProbeResponse, {}), now);
      }
      return;
  }
}

void PtpIpCameraServer::OnNewcomer(PtpIpConnection& c, const Packet& packet,
                                   Clock::time_point now) {
  if (packet.type == PacketType::kInitCommandRequest) {
    // Parsed before anything changes: a malformed request costs only the newcomer.
    ParseInitCommandRequest(packet);  // any initiator is welcome; the GUID is not checked
    // A new command connection replaces the old initiator, as a body does when the
    // computer reconnects; the card and the settings stay.
    for (const auto& other : connections_) {
      if (other.get() != &c && other->role != ConnectionRole::kNewcomer) other->closed = true;
    }
    c.role = ConnectionRole::kCommand;
    do {
      c.number = static_cast<std::uint32_t>(numbers_());
    } while (c.number == 0);
    {
      std::lock_guard lock(mutex_);
      responder_.ResetSession();
      ++counters_.connections;
    }
    c.Queue(EncodePacket(PacketType::kInitCommandAck,
                         InitCommandAckPayload(c.number, kCameraGuid, options_.offer.model)),
            now);
    return;
  }
  if (packet.type == PacketType::kInitEventRequest) {
    // The event connection belongs to the command connection whose number it names; anyone
    // else would steal the initiator's events.
    PtpIpConnection* command = Find(ConnectionRole::kCommand);
    const bool matches = command != nullptr && packet.payload.size() >= 4 &&
                         PtpReader(packet.payload).U32() == command->number;
    if (matches) {
      if (PtpIpConnection* old = Find(ConnectionRole::kEvent)) old->closed = true;
      c.role = ConnectionRole::kEvent;
      c.Queue(EncodePacket(PacketType::kInitEventAck, {}), now);
      return;
    }
  }
  std::fprintf(stderr, "simulated camera: unexpected first packet (type %s); refusing it\n",
               PacketTypeName(packet.type).c_str());
  c.Queue(EncodePacket(PacketType::kInitFail, {1, 0, 0, 0}), now);
  c.close_when_sent = true;
}

void PtpIpCameraServer::OnCommand(PtpIpConnection& c, const Packet& packet, Clock::time_point now) {
  if (c.data_in) {
    if (!c.data_in->Add(packet)) return;
    const OperationRequest request = *c.request;
    const std::vector<std::uint8_t> data = c.data_in->Take();
    c.request.reset();
    c.data_in.reset();
    Dispatch(c, request, data, now);
    return;
  }
  if (packet.type == PacketType::kProbeRequest) {
    c.Queue(EncodePacket(PacketType::kProbeResponse, {}), now);
    return;
  }
  if (packet.type != PacketType::kOperationRequest) {
    throw Error("unexpected packet type " + PacketTypeName(packet.type) +
                " on the command connection");
  }
  const OperationRequest request = ParseOperationRequest(packet);
  if (request.data_phase == kDataPhaseToCamera) {
    c.request = request;
    c.data_in.emplace(request.transaction);
    c.phase_started = now;
    return;
  }
  Dispatch(c, request, {}, now);
}

void PtpIpCameraServer::Dispatch(PtpIpConnection& c, const OperationRequest& request,
                                 const std::vector<std::uint8_t>& data, Clock::time_point now) {
  PtpReply reply;
  double delay_s = 0;
  bool drop = false;
  {
    std::lock_guard lock(mutex_);
    ++counters_.operations;
    delay_s = faults_.response_delay_s;
    if (request.code == op::kInitiateCapture && faults_.vanish_s > 0) {
      back_at_ = now + std::chrono::duration_cast<Clock::duration>(
                           std::chrono::duration<double>(faults_.vanish_s));
      faults_.vanish_s = 0;
      ++counters_.vanished;
      vanished_ = true;
      return;
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
  // The delay holds this reply back; the loop serves every other connection meanwhile.
  const Clock::time_point send_at =
      now + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(delay_s));
  if (drop) {
    // Start data announces the file, then the link dies: the initiator sees a broken stream.
    PtpWriter start;
    start.U32(request.transaction).U64(reply.data->size());
    c.Queue(EncodePacket(PacketType::kStartData, start.bytes()), send_at);
    c.close_when_sent = true;
    return;
  }
  if (reply.data) c.Queue(EncodeDataPhase(request.transaction, *reply.data), send_at);
  c.Queue(EncodePacket(PacketType::kOperationResponse,
                       ResponsePayload(reply.code, request.transaction, reply.params)),
          send_at);
  c.after = std::move(reply.after);
  c.after_transaction = request.transaction;
}

void PtpIpCameraServer::RunAfterWork(PtpIpConnection& c, Clock::time_point now) {
  // After the response has gone, as a body answers the shutter release first.
  if (c.role != ConnectionRole::kCommand || !c.after || c.unsent() > 0) return;
  std::vector<PtpEvent> events;
  {
    std::lock_guard lock(mutex_);
    events = c.after();
  }
  c.after = nullptr;
  PtpIpConnection* event = Find(ConnectionRole::kEvent);
  if (event == nullptr) return;
  for (const PtpEvent& e : events) {
    event->Queue(
        EncodePacket(PacketType::kEvent, EventPayload(e.code, c.after_transaction, e.params)), now);
  }
  if (event->unsent() > options_.limits.max_event_backlog) {
    Close(*event, "the event connection does not read its events");
  } else if (!event->Flush(now)) {
    Close(*event, "");
  }
}

void PtpIpCameraServer::CheckDeadlines(PtpIpConnection& c, Clock::time_point now) {
  const ConnectionLimits& limits = options_.limits;
  if (c.role == ConnectionRole::kNewcomer && !c.close_when_sent &&
      now - c.accepted > limits.init_timeout) {
    Close(c, "no init request within " + std::to_string(limits.init_timeout.count()) + " ms");
  } else if (c.mid_packet() && now - c.packet_started() > limits.packet_timeout) {
    Close(c, "a packet incomplete after " + std::to_string(limits.packet_timeout.count()) + " ms");
  } else if (c.data_in && now - c.phase_started > limits.packet_timeout) {
    Close(c,
          "a data phase incomplete after " + std::to_string(limits.packet_timeout.count()) + " ms");
  } else if (c.ready_to_send(now) && now - c.last_progress() > limits.send_timeout) {
    Close(c, "the peer read nothing for " + std::to_string(limits.send_timeout.count()) + " ms");
  }
}

}  // namespace brdfrig::simcamera
