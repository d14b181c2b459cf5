#include "acquire/daemon_config.h"

#include <cstdio>

#include "common/atomic_file.h"
#include "common/yaml_reader.h"

namespace brdfrig::acquire {

namespace fs = std::filesystem;

void DaemonConfig::Validate() const {
  if (data_dir.empty()) throw OptionsError("daemon: data_dir is required");
  if (rig_file.empty()) throw OptionsError("daemon: rig is required");
  if (socket.empty()) throw OptionsError("daemon: socket path is empty");
  if (tcp_port != 0 && token.size() < 16) {
    throw OptionsError("daemon: the TCP listener needs a token of at least 16 characters");
  }
  run.Validate();
  hand_off.Validate();
}

DaemonConfig LoadDaemonConfig(const fs::path& file) {
  const YamlNode root = LoadYamlFile(file.string());
  const fs::path base = file.parent_path();
  auto resolve = [&](const std::string& p) {
    return fs::path(p).is_absolute() ? fs::path(p) : base / p;
  };
  DaemonConfig config;
  config.data_dir = resolve(root.Required("data_dir").AsString());
  config.rig_file = resolve(root.Required("rig").AsString());
  config.socket = root.Has("socket") ? resolve(root.Required("socket").AsString())
                                     : config.data_dir / "daemon.sock";
  config.resume_interrupted = root.Get("resume_interrupted", false);
  if (auto tcp = root.Optional("tcp")) {
    const YamlNode port = tcp->Required("port");
    config.tcp_port = static_cast<int>(port.InRange(port.AsInt(), 1, 65535));
    const YamlNode token_file = tcp->Required("token_file");
    const fs::path token_path = resolve(token_file.AsString());
    // The token is the only access control on TCP: a copy others can read is no secret.
    std::error_code error;
    const fs::perms mode = fs::status(token_path, error).permissions();
    if (!error && (mode & (fs::perms::group_all | fs::perms::others_all)) != fs::perms::none) {
      char octal[8];
      std::snprintf(octal, sizeof octal, "%04o", static_cast<unsigned>(mode) & 07777);
      token_file.Fail("the token file " + token_path.string() + " has mode " + octal +
                      ": others may read it; `chmod 600` it");
    }
    std::string token = ReadFileToString(token_path);
    while (!token.empty() &&
           (token.back() == '\n' || token.back() == '\r' || token.back() == ' ')) {
      token.pop_back();
    }
    if (token.size() < 16) token_file.Fail("the token must have at least 16 characters");
    config.token = token;
    tcp->Finish();
  }
  if (auto retry = root.Optional("retry")) {
    RetryPolicy& r = config.run.retry;
    if (auto n = retry->Optional("max_attempts"))
      r.max_attempts = static_cast<int>(n->InRange(n->AsInt(), 1, 100));
    if (auto n = retry->Optional("initial_backoff_s"))
      r.initial_backoff_s = n->InRange(n->AsDouble(), 0, 600);
    if (auto n = retry->Optional("max_backoff_s"))
      r.max_backoff_s = n->InRange(n->AsDouble(), 0, 3600);
    if (auto n = retry->Optional("max_position_redos"))
      r.max_position_redos = static_cast<int>(n->InRange(n->AsInt(), 0, 100));
    retry->Finish();
  }
  if (auto hand_off = root.Optional("hand_off")) {
    const YamlNode command = hand_off->Required("command");
    if (!command.IsSequence() || command.Elements().empty()) {
      command.Fail("expected a list: the program (absolute path) and its arguments");
    }
    for (const YamlNode& argument : command.Elements()) {
      config.hand_off.command.push_back(argument.AsString());
    }
    if (auto timeout = hand_off->Optional("timeout_s")) {
      config.hand_off.timeout_s = timeout->InRange(timeout->AsDouble(), 0.1, 86400);
    }
    try {
      config.hand_off.Validate();
    } catch (const OptionsError& e) {
      command.Fail(e.what());
    }
    hand_off->Finish();
  }
  root.Finish();
  config.Validate();
  return config;
}

}  // namespace brdfrig::acquire
