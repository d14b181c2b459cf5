#include "simcamera/ptpip_connection.h"

#include <fcntl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>

#include "common/error.h"

namespace brdfrig::simcamera {
namespace {

// Reads per call at most this many times: one busy peer does not starve the others.
constexpr int kReadsPerCall = 64;

}  // namespace

PtpIpConnection::PtpIpConnection(int fd, Clock::time_point now) : accepted(now), fd_(fd) {
  const int flags = fcntl(fd_, F_GETFL, 0);
  fcntl(fd_, F_SETFL, flags | O_NONBLOCK);
}

PtpIpConnection::~PtpIpConnection() {
  if (fd_ >= 0) close(fd_);
}

void PtpIpConnection::CloseSocket() {
  if (fd_ >= 0) close(fd_);
  fd_ = -1;
  closed = true;
}

std::optional<Packet> PtpIpConnection::Receive(Clock::time_point now) {
  std::uint8_t buffer[1 << 16];
  for (int i = 0; i < kReadsPerCall && !peer_closed_; ++i) {
    const std::size_t want = std::min(in_.wanted(), sizeof buffer);
    const ssize_t n = recv(fd_, buffer, want, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) return std::nullopt;
    if (n <= 0) {
      peer_closed_ = true;
      if (in_.mid_packet()) throw Error("PTP/IP: the connection broke inside a packet");
      return std::nullopt;
    }
    if (!in_.mid_packet()) packet_started_ = now;
    in_.Append(buffer, static_cast<std::size_t>(n));
    if (std::optional<Packet> packet = in_.Take()) return packet;
  }
  return std::nullopt;
}

void PtpIpConnection::Queue(const std::vector<std::uint8_t>& bytes, Clock::time_point not_before) {
  if (unsent() == 0) {
    out_.clear();
    out_at_ = 0;
    send_at_ = not_before;
    last_progress_ = not_before;
  }
  out_.insert(out_.end(), bytes.begin(), bytes.end());
}

bool PtpIpConnection::Flush(Clock::time_point now) {
  while (ready_to_send(now)) {
    const ssize_t n = send(fd_, out_.data() + out_at_, unsent(), MSG_NOSIGNAL | MSG_DONTWAIT);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) return true;
    if (n <= 0) return false;
    out_at_ += static_cast<std::size_t>(n);
    last_progress_ = now;
  }
  if (unsent() == 0) {
    // The reply has gone: its memory is released, not kept for the connection's lifetime.
    std::vector<std::uint8_t>().swap(out_);
    out_at_ = 0;
  }
  return true;
}

}  // namespace brdfrig::simcamera
