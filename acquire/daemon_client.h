// The client side of the daemon's control API (the `brdfrig submit|status|pause|resume|abort`
// commands and the tests): one HTTP/1.1 request per connection over the Unix socket (or
// loopback TCP with a bearer token).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "common/error.h"

namespace brdfrig::acquire {

// The daemon answered with an error status; what() is its reason.
class DaemonError : public Error {
 public:
  DaemonError(int status, const std::string& reason)
      : Error("daemon: " + reason + " (HTTP " + std::to_string(status) + ")"), status_(status) {}
  int status() const { return status_; }

 private:
  int status_;
};

struct DaemonReply {
  int status = 0;
  nlohmann::json body;
};

class DaemonClient {
 public:
  explicit DaemonClient(std::filesystem::path socket) : socket_(std::move(socket)) {}
  DaemonClient(int tcp_port, std::string token) : port_(tcp_port), token_(std::move(token)) {}

  // Any request; does not throw on error statuses (for tests of the API itself).
  DaemonReply Request(const std::string& method, const std::string& path,
                      const std::string& body = "");

  // The API's operations; throw DaemonError on an error status.
  // `plan_source` names the plan's text in errors (its file, for the command line); the name
  // and the plan must be UTF-8 (they travel as JSON strings): anything else is refused here,
  // at its line and column, before a request is made.
  nlohmann::json Submit(const std::string& name, const std::string& plan_text,
                        const std::string& plan_source = "plan");
  nlohmann::json Status();
  nlohmann::json Sessions();
  nlohmann::json Pause();
  nlohmann::json Resume();
  nlohmann::json Abort(const std::string& reason = "");
  nlohmann::json ResumeSession(const std::string& name);

 private:
  nlohmann::json Expect(DaemonReply reply);
  int Connect();

  std::filesystem::path socket_;
  int port_ = 0;
  std::string token_;
};

}  // namespace brdfrig::acquire
