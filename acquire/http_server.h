// A minimal HTTP/1.1 server on sockets the caller created (libmicrohttpd with
// MHD_OPTION_LISTEN_SOCKET, so a Unix domain socket works as well as TCP). Requests are
// handed over complete (body included, at most kMaxBody bytes) to one handler function.
#pragma once

#include <cstddef>
#include <functional>
#include <string>

struct MHD_Daemon;

namespace brdfrig::acquire {

struct HttpRequest {
  std::string method;  // "GET", "POST", ...
  std::string path;    // "/v1/status"
  std::string body;
  std::string authorization;  // the Authorization header, "" when absent
};

struct HttpResponse {
  int status = 200;
  std::string body;  // JSON
};

class HttpServer {
 public:
  using Handler = std::function<HttpResponse(const HttpRequest&)>;
  static constexpr std::size_t kMaxBody = 1 << 20;
  // A connection that sends nothing for this long is closed (idle or slow clients).
  static constexpr unsigned kIdleTimeoutS = 5;
  // Open connections at once (each costs a descriptor, not a thread).
  static constexpr unsigned kConnectionLimit = 512;
  // Threads serving requests: one slow request does not hold up the others.
  static constexpr unsigned kThreads = 4;

  // Takes ownership of the listening socket. `bearer_token`: when not empty, every request
  // must carry "Authorization: Bearer <token>" (else 401).
  HttpServer(int listen_fd, Handler handler, std::string bearer_token = "");
  ~HttpServer();
  HttpServer(const HttpServer&) = delete;
  HttpServer& operator=(const HttpServer&) = delete;

  // Used by libmicrohttpd's callbacks.
  HttpResponse Dispatch(const HttpRequest& request) const;

 private:
  Handler handler_;
  std::string token_;
  MHD_Daemon* daemon_ = nullptr;
};

}  // namespace brdfrig::acquire
