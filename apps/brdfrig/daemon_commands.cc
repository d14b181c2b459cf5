#include "apps/brdfrig/daemon_commands.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <thread>

#include "acquire/daemon.h"
#include "acquire/daemon_client.h"
#include "acquire/progress_json.h"
#include "apps/brdfrig/progress_line.h"
#include "common/atomic_file.h"

namespace brdfrig::apps {
namespace {

using nlohmann::json;

struct ClientArgs {
  std::string socket;
  std::string config;
  std::string name;
  std::string plan;
  std::string reason;
  bool follow = false;
  bool json_output = false;
};

void AddConnectionOptions(CLI::App* cmd, ClientArgs& args) {
  cmd->add_option("--socket", args.socket,
                  "The daemon's socket (default: $BRDFRIG_SOCKET, else from --config)");
  cmd->add_option("--config", args.config, "daemon.yaml, to find the socket");
}

acquire::DaemonClient Connect(const ClientArgs& args) {
  if (!args.socket.empty()) return acquire::DaemonClient(args.socket);
  if (const char* env = std::getenv("BRDFRIG_SOCKET")) return acquire::DaemonClient(env);
  if (!args.config.empty()) {
    return acquire::DaemonClient(acquire::LoadDaemonConfig(args.config).socket);
  }
  throw OptionsError("where is the daemon? give --socket, --config or $BRDFRIG_SOCKET");
}

// Shows the progress until the daemon is idle (every queued session done).
void Follow(acquire::DaemonClient& client) {
  ProgressLine line;
  for (;;) {
    const json status = client.Status();
    if (status.contains("progress")) line.Show(acquire::ProgressFromJson(status["progress"]));
    if (status["state"] == "idle" && status["queue"].empty()) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
  }
  line.Finish();
  std::printf("%s\n", client.Status().value("last_result", "").c_str());
}

void PrintStatus(const json& status) {
  std::printf("daemon %s", status["state"].get<std::string>().c_str());
  if (!status["session"].is_null()) {
    std::printf(": session %s", status["session"].get<std::string>().c_str());
  }
  std::printf("\n");
  if (status.contains("progress")) {
    const acquire::RunProgress p = acquire::ProgressFromJson(status["progress"]);
    std::printf(
        "  %s, position %d/%d, frame %d/%d, %d/%d frames recorded, ETA %.0f s, last "
        "frame %.2f%% saturated\n",
        acquire::RunStateName(p.state), p.position + 1, p.positions, p.frame + 1,
        p.frames_per_position, p.frames_recorded, p.frames_total, p.eta_s, 100 * p.last_saturation);
    if (!p.message.empty()) std::printf("  %s\n", p.message.c_str());
  }
  if (!status["queue"].empty()) std::printf("  queued: %s\n", status["queue"].dump().c_str());
  const std::string last = status.value("last_result", "");
  if (!last.empty()) std::printf("  last: %s\n", last.c_str());
}

}  // namespace

void RegisterDaemonCommands(CLI::App& app) {
  auto config = std::make_shared<std::string>();
  CLI::App* daemon = app.add_subcommand(
      "daemon", "Run the acquisition daemon: owns the rig, runs submitted plans one at a time");
  daemon->add_option("--config", *config, "daemon.yaml")->required();
  daemon->callback([config] { acquire::ServeUntilSignal(acquire::LoadDaemonConfig(*config)); });

  auto args = std::make_shared<ClientArgs>();
  CLI::App* submit = app.add_subcommand("submit", "Queue a plan on the daemon");
  AddConnectionOptions(submit, *args);
  submit->add_option("plan", args->plan, "plan.yaml")->required();
  submit->add_option("--name", args->name, "Session name (letters, digits, . _ -)")->required();
  submit->add_flag("--follow", args->follow, "Show the progress until the daemon is idle");
  submit->callback([args] {
    acquire::DaemonClient client = Connect(*args);
    const json reply = client.Submit(args->name, ReadFileToString(args->plan), args->plan);
    std::printf("session %s queued (place %d)\n", args->name.c_str(), reply.value("place", 0));
    if (reply.contains("warnings")) {
      for (const json& w : reply["warnings"]) {
        std::printf("warning: %s\n", w.get<std::string>().c_str());
      }
    }
    if (args->follow) Follow(client);
  });

  CLI::App* status = app.add_subcommand("status", "Show what the daemon is doing");
  AddConnectionOptions(status, *args);
  status->add_flag("--follow", args->follow, "Show the progress until the daemon is idle");
  status->add_flag("--json", args->json_output, "Print the raw JSON (status and sessions)");
  status->callback([args] {
    acquire::DaemonClient client = Connect(*args);
    if (args->json_output) {
      std::printf("%s\n%s\n", client.Status().dump(2).c_str(), client.Sessions().dump(2).c_str());
      return;
    }
    if (args->follow) {
      Follow(client);
      return;
    }
    PrintStatus(client.Status());
    const json sessions = client.Sessions();  // kept alive for the loop below
    for (const json& s : sessions["sessions"]) {
      std::printf("  %-24s %-12s %3d frames%s\n", s.value("name", "").c_str(),
                  s.value("exit_status", s.value("error", "")).c_str(), s.value("frames", 0),
                  s.value("resumable", false) ? "  (resumable)" : "");
    }
  });

  CLI::App* pause = app.add_subcommand("pause", "Pause the running session at a safe point");
  AddConnectionOptions(pause, *args);
  pause->callback([args] {
    Connect(*args).Pause();
    std::printf("pause requested\n");
  });

  CLI::App* resume = app.add_subcommand(
      "resume", "Resume the paused session, or queue an interrupted one with --session");
  AddConnectionOptions(resume, *args);
  resume->add_option("--session", args->name, "Interrupted session to resume");
  resume->callback([args] {
    acquire::DaemonClient client = Connect(*args);
    if (args->name.empty()) {
      client.Resume();
      std::printf("resume requested\n");
    } else {
      client.ResumeSession(args->name);
      std::printf("session %s queued for resume\n", args->name.c_str());
    }
  });

  CLI::App* abort = app.add_subcommand("abort", "Abort the running session (it stays resumable)");
  AddConnectionOptions(abort, *args);
  abort->add_option("--reason", args->reason, "Recorded in the session's stop record");
  abort->callback([args] {
    Connect(*args).Abort(args->reason);
    std::printf("abort requested\n");
  });
}

}  // namespace brdfrig::apps
