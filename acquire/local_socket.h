// Listening and connecting sockets for the daemon's control API: a Unix domain socket that
// only its owner can use (mode 0600), and an optional TCP socket bound to loopback only.
#pragma once

#include <filesystem>
#include <string>

namespace brdfrig::acquire {

// Binds and listens on `path` with mode 0600. A stale socket file (nobody listening) is
// replaced; a live one or a non-socket file is an error. Returns the file descriptor.
int ListenUnixSocket(const std::filesystem::path& path);
// Binds and listens on 127.0.0.1:port (0 = any free port). Returns the file descriptor.
int ListenLoopbackTcp(int port);
// The port a listening TCP socket is bound to.
int BoundPort(int fd);

// Connected sockets for clients. Throw brdfrig::Error saying what could not be reached.
int ConnectUnixSocket(const std::filesystem::path& path);
int ConnectLoopbackTcp(int port);

}  // namespace brdfrig::acquire
