#include "apps/brdfrig/acquire_commands.h"

#include <signal.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <mutex>
#include <thread>

#include "acquire/capture.h"
#include "acquire/plan_check.h"
#include "apps/brdfrig/progress_line.h"
#include "common/atomic_file.h"
#include "coverage/coverage.h"
#include "session/session_verify.h"

namespace brdfrig::apps {
namespace {

struct CaptureArgs {
  std::string rig, plan, output;
  bool resume = false;
  bool serial = false;
  int max_attempts = 5;
};

// Ctrl-C / SIGTERM / SIGHUP (the terminal or SSH session closed) abort the run cleanly (axes
// stopped, downloaded frames recorded, stop record written) instead of killing it mid-write; a
// second one exits at once. The signals are blocked in every thread and taken by one watcher
// thread, which only touches the engine while RunCapture says it exists.
class AbortOnSignal {
 public:
  AbortOnSignal() {
    sigemptyset(&set_);
    sigaddset(&set_, SIGINT);
    sigaddset(&set_, SIGTERM);
    sigaddset(&set_, SIGHUP);
    pthread_sigmask(SIG_BLOCK, &set_, nullptr);  // before any thread exists: all inherit it
    thread_ = std::thread([this] {
      const timespec tick{0, 200'000'000};
      bool aborting = false;
      while (!done_) {
        const int sig = sigtimedwait(&set_, nullptr, &tick);
        if (sig <= 0) continue;
        if (aborting) std::_Exit(128 + sig);  // the second signal: the user insists
        aborting = true;
        const char* name = sig == SIGINT ? "SIGINT" : sig == SIGHUP ? "SIGHUP" : "SIGTERM";
        std::fprintf(stderr, "\nbrdfrig: %s received, aborting the run (again to exit now)\n",
                     name);
        std::lock_guard lock(mutex_);
        if (engine_ != nullptr) {
          engine_->Abort(sig == SIGINT   ? "interrupted (Ctrl-C)"
                         : sig == SIGHUP ? "hung up (SIGHUP: the terminal closed)"
                                         : "terminated (SIGTERM)");
        }
      }
    });
  }
  ~AbortOnSignal() {
    done_ = true;
    thread_.join();
    pthread_sigmask(SIG_UNBLOCK, &set_, nullptr);
  }
  // For CaptureOptions::on_engine: the engine while it exists, nullptr before it goes.
  void SetEngine(acquire::RunEngine* engine) {
    std::lock_guard lock(mutex_);
    engine_ = engine;
  }

 private:
  sigset_t set_;
  std::atomic<bool> done_{false};
  std::mutex mutex_;
  acquire::RunEngine* engine_ = nullptr;
  std::thread thread_;
};

}  // namespace

void RegisterAcquireCommands(CLI::App& app) {
  CLI::App* plan = app.add_subcommand("plan", "Capture plans");
  plan->require_subcommand(1);
  struct CheckArgs {
    std::string rig, plan, svg;
    bool json = false;
  };
  auto check_args = std::make_shared<CheckArgs>();
  CLI::App* check = plan->add_subcommand(
      "check",
      "Dry run of a plan against a rig: limits, duration, highlight, (θh, θd) coverage; resolves "
      "and explains a designed plan");
  check->add_option("--rig", check_args->rig, "rig.yaml")->required();
  check->add_option("--plan", check_args->plan, "plan.yaml")->required();
  check->add_flag("--json", check_args->json,
                  "Print resolved positions (degrees), exposures and coverage as JSON");
  check->add_option("--svg", check_args->svg, "Write the coverage map (θh × θd) as SVG");
  check->callback([check_args] {
    const acquire::Plan p = acquire::LoadPlanFile(check_args->plan);
    const acquire::PlanCheckReport report =
        acquire::CheckPlan(p, rig::ReadRigDescription(check_args->rig));
    std::printf("%s", check_args->json ? report.ToJson().c_str() : report.ToString().c_str());
    if (!check_args->svg.empty() && report.has_coverage) {
      WriteFileAtomically(check_args->svg, coverage::CoverageSvg(
                                               report.coverage, "coverage of " + check_args->plan));
    }
    if (!report.ok()) throw Error("the plan cannot run on this rig (errors above)");
  });

  auto args = std::make_shared<CaptureArgs>();
  CLI::App* capture =
      app.add_subcommand("capture", "Run a capture session in the foreground (no daemon)");
  capture->add_option("--rig", args->rig, "rig.yaml")->required();
  capture->add_option("--plan", args->plan, "plan.yaml (optional with --resume)");
  capture->add_option("-o,--output", args->output, "Session directory to create")->required();
  capture->add_flag("--resume", args->resume,
                    "Continue the session in -o (redo its incomplete position); starts it when "
                    "it does not exist");
  capture->add_flag("--serial", args->serial,
                    "Record each frame before moving on (no overlap; for comparison)");
  capture->add_option("--max-attempts", args->max_attempts,
                      "Tries per move or shot on recoverable faults (default 5)");
  capture->callback([args] {
    acquire::CaptureOptions options;
    options.rig_file = args->rig;
    options.plan_file = args->plan;
    options.output_dir = args->output;
    options.resume = args->resume;
    options.run.overlap = !args->serial;
    options.run.retry.max_attempts = args->max_attempts;
    ProgressLine line;
    options.on_progress = [&line](const acquire::RunProgress& p) { line.Show(p); };
    AbortOnSignal signals;
    options.on_engine = [&signals](acquire::RunEngine* engine) { signals.SetEngine(engine); };
    const acquire::CaptureSummary summary = acquire::RunCapture(options);
    line.Finish();
    for (const std::string& w : summary.warnings) std::printf("warning: %s\n", w.c_str());
    std::printf("%s\n", summary.ToString().c_str());
    if (summary.run.status != acquire::ExitStatus::kSuccess) {
      throw Error(std::string("capture ") + acquire::ExitStatusName(summary.run.status) +
                  "; continue it with --resume");
    }
  });

  CLI::App* session = app.add_subcommand("session", "Inspect capture sessions");
  session->require_subcommand(1);
  auto dir = std::make_shared<std::string>();
  CLI::App* verify = session->add_subcommand(
      "verify", "Re-hash every frame; report missing, extra or changed files");
  verify->add_option("dir", *dir, "Session directory")->required();
  verify->callback([dir] {
    const session::VerifyReport report = session::VerifySession(*dir);
    std::printf("%s", report.ToString().c_str());
    if (!report.ok()) throw Error("session " + *dir + " does not match its catalog");
  });
}

}  // namespace brdfrig::apps
