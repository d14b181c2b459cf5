#include "acquire/daemon_client.h"

#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "acquire/local_socket.h"
#include "common/json_parse.h"
#include "common/utf8.h"

namespace brdfrig::acquire {
namespace {

void WriteAll(int fd, const std::string& data) {
  std::size_t sent = 0;
  while (sent < data.size()) {
    const ssize_t n = ::send(fd, data.data() + sent, data.size() - sent, MSG_NOSIGNAL);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw Error(std::string("daemon: cannot send the request: ") + std::strerror(errno));
    }
    sent += static_cast<std::size_t>(n);
  }
}

std::string ReadAll(int fd) {
  std::string data;
  char buffer[8192];
  for (;;) {
    const ssize_t n = ::recv(fd, buffer, sizeof buffer, 0);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw Error(std::string("daemon: cannot read the answer: ") + std::strerror(errno));
    }
    if (n == 0) return data;
    data.append(buffer, static_cast<std::size_t>(n));
  }
}

}  // namespace

int DaemonClient::Connect() {
  return socket_.empty() ? ConnectLoopbackTcp(port_) : ConnectUnixSocket(socket_);
}

DaemonReply DaemonClient::Request(const std::string& method, const std::string& path,
                                  const std::string& body) {
  std::string request = method + " " + path + " HTTP/1.1\r\nHost: localhost\r\n" +
                        "Connection: close\r\nContent-Type: application/json\r\n" +
                        "Content-Length: " + std::to_string(body.size()) + "\r\n";
  if (!token_.empty()) request += "Authorization: Bearer " + token_ + "\r\n";
  request += "\r\n" + body;
  const int fd = Connect();
  std::string answer;
  try {
    WriteAll(fd, request);
    answer = ReadAll(fd);
  } catch (...) {
    ::close(fd);
    throw;
  }
  ::close(fd);
  DaemonReply reply;
  const std::size_t space = answer.find(' ');
  const std::size_t header_end = answer.find("\r\n\r\n");
  if (!answer.starts_with("HTTP/1.") || space == std::string::npos ||
      header_end == std::string::npos) {
    throw Error("daemon: malformed answer");
  }
  reply.status = std::atoi(answer.c_str() + space + 1);
  const std::string content = answer.substr(header_end + 4);
  try {
    reply.body = content.empty() ? nlohmann::json::object() : ParseJson(content, "daemon answer");
  } catch (const FileError&) {
    reply.body = nlohmann::json::value_t::discarded;  // as before: the status tells the rest
  }
  return reply;
}

nlohmann::json DaemonClient::Expect(DaemonReply reply) {
  if (reply.status >= 400) {
    const std::string reason = reply.body.is_object() && reply.body.contains("error")
                                   ? reply.body["error"].get<std::string>()
                                   : "request refused";
    throw DaemonError(reply.status, reason);
  }
  return reply.body;
}

nlohmann::json DaemonClient::Submit(const std::string& name, const std::string& plan_text,
                                    const std::string& plan_source) {
  RequireUtf8(name, "session name");
  RequireUtf8(plan_text, plan_source);
  return Expect(
      Request("POST", "/v1/sessions", nlohmann::json{{"name", name}, {"plan", plan_text}}.dump()));
}
nlohmann::json DaemonClient::Status() { return Expect(Request("GET", "/v1/status")); }
nlohmann::json DaemonClient::Sessions() { return Expect(Request("GET", "/v1/sessions")); }
nlohmann::json DaemonClient::Pause() { return Expect(Request("POST", "/v1/pause")); }
nlohmann::json DaemonClient::Resume() { return Expect(Request("POST", "/v1/resume")); }
nlohmann::json DaemonClient::Abort(const std::string& reason) {
  return Expect(Request("POST", "/v1/abort",
                        reason.empty() ? "" : nlohmann::json{{"reason", reason}}.dump()));
}
nlohmann::json DaemonClient::ResumeSession(const std::string& name) {
  return Expect(Request("POST", "/v1/sessions/" + name + "/resume"));
}

}  // namespace brdfrig::acquire
