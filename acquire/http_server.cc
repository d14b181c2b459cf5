#include "acquire/http_server.h"

#include <microhttpd.h>
#include <unistd.h>

#include <cstring>
#include <nlohmann/json.hpp>

#include "common/error.h"

namespace brdfrig::acquire {
namespace {

struct PendingRequest {
  std::string body;
  bool too_large = false;
};

// Compares without an early exit, so that response time says nothing about the token.
bool SameSecret(const std::string& a, const std::string& b) {
  unsigned char diff = a.size() == b.size() ? 0 : 1;
  for (std::size_t i = 0; i < a.size(); ++i) {
    diff |= static_cast<unsigned char>(a[i] ^ (i < b.size() ? b[i] : 0));
  }
  return diff == 0;
}

HttpResponse ErrorResponse(int status, const std::string& reason) {
  // `reason` may quote a client's bytes: invalid UTF-8 is replaced, never thrown.
  return {status, nlohmann::json{{"error", reason}}.dump(-1, ' ', false,
                                                         nlohmann::json::error_handler_t::replace)};
}

MHD_Result Send(MHD_Connection* connection, const HttpResponse& response) {
  MHD_Response* r = MHD_create_response_from_buffer(
      response.body.size(), const_cast<char*>(response.body.data()), MHD_RESPMEM_MUST_COPY);
  MHD_add_response_header(r, "Content-Type", "application/json");
  const MHD_Result result = MHD_queue_response(connection, response.status, r);
  MHD_destroy_response(r);
  return result;
}

MHD_Result OnRequest(void* cls, MHD_Connection* connection, const char* url, const char* method,
                     const char* /*version*/, const char* upload_data, size_t* upload_size,
                     void** con_cls) {
  const auto* server = static_cast<const HttpServer*>(cls);
  if (*con_cls == nullptr) {  // first call: headers only
    *con_cls = new PendingRequest;
    return MHD_YES;
  }
  auto* pending = static_cast<PendingRequest*>(*con_cls);
  if (*upload_size != 0) {
    if (pending->body.size() + *upload_size > HttpServer::kMaxBody) {
      pending->too_large = true;
    } else {
      pending->body.append(upload_data, *upload_size);
    }
    *upload_size = 0;
    return MHD_YES;
  }
  if (pending->too_large) {
    return Send(connection, ErrorResponse(413, "request body larger than 1 MiB"));
  }
  HttpRequest request;
  request.method = method;
  request.path = url;
  request.body = std::move(pending->body);
  const char* auth = MHD_lookup_connection_value(connection, MHD_HEADER_KIND, "Authorization");
  request.authorization = auth ? auth : "";
  return Send(connection, server->Dispatch(request));
}

void OnCompleted(void* /*cls*/, MHD_Connection* /*connection*/, void** con_cls,
                 MHD_RequestTerminationCode /*code*/) {
  delete static_cast<PendingRequest*>(*con_cls);
  *con_cls = nullptr;
}

}  // namespace

HttpServer::HttpServer(int listen_fd, Handler handler, std::string bearer_token)
    : handler_(std::move(handler)), token_(std::move(bearer_token)) {
  // The control API must answer an emergency abort whatever other clients do: idle or slow
  // connections are dropped after kIdleTimeoutS, the connection limit is far above what a
  // lab needs (64 idle clients once locked everyone out for 30 s), and a pool of threads
  // serves requests, so one slow handler (a large session list, a plan being designed)
  // leaves the others free.
  daemon_ = MHD_start_daemon(
      MHD_USE_INTERNAL_POLLING_THREAD | MHD_USE_POLL, 0, nullptr, nullptr, &OnRequest, this,
      MHD_OPTION_LISTEN_SOCKET, listen_fd, MHD_OPTION_NOTIFY_COMPLETED, &OnCompleted, nullptr,
      MHD_OPTION_CONNECTION_TIMEOUT, kIdleTimeoutS, MHD_OPTION_CONNECTION_LIMIT, kConnectionLimit,
      MHD_OPTION_THREAD_POOL_SIZE, kThreads, MHD_OPTION_END);
  if (daemon_ == nullptr) {
    ::close(listen_fd);
    throw Error("cannot start the HTTP server (libmicrohttpd) on the control socket");
  }
}

// MHD_stop_daemon closes the listening socket too (also one given with
// MHD_OPTION_LISTEN_SOCKET); closing it again could close a descriptor reused meanwhile.
HttpServer::~HttpServer() { MHD_stop_daemon(daemon_); }

HttpResponse HttpServer::Dispatch(const HttpRequest& request) const {
  if (!token_.empty() && !SameSecret(request.authorization, "Bearer " + token_)) {
    return ErrorResponse(401, "missing or wrong bearer token");
  }
  try {
    return handler_(request);
  } catch (const std::exception& e) {
    return ErrorResponse(500, e.what());
  }
}

}  // namespace brdfrig::acquire
