#include "acquire/hand_off.h"

#include <cmath>
#include <sstream>
#include <vector>

#include "common/error.h"
#include "common/subprocess.h"

namespace brdfrig::acquire {

namespace {

// One pass over the argument as written: a session directory that itself contains "{name}"
// (a data_dir of that name) stays the directory it is.
std::string Substitute(const std::string& argument, const std::string& session,
                       const std::string& name) {
  static const std::string kSession = "{session}", kName = "{name}";
  std::string out;
  for (std::size_t i = 0; i < argument.size();) {
    if (argument.compare(i, kSession.size(), kSession) == 0) {
      out += session;
      i += kSession.size();
    } else if (argument.compare(i, kName.size(), kName) == 0) {
      out += name;
      i += kName.size();
    } else {
      out += argument[i++];
    }
  }
  return out;
}

std::string LastLine(std::string text) {
  while (!text.empty() && text.back() == '\n') text.pop_back();
  const std::size_t newline = text.rfind('\n');
  return newline == std::string::npos ? text : text.substr(newline + 1);
}

std::string Seconds(double s) {
  std::ostringstream text;
  text << s << " s";
  return text.str();
}

}  // namespace

void HandOff::Validate() const {
  if (command.empty()) return;
  if (!std::filesystem::path(command.front()).is_absolute()) {
    throw OptionsError("HandOff.command[0] = " + command.front() +
                       "; must be an absolute path (a service's PATH is not a shell's)");
  }
  bool names_session = false;
  for (const std::string& argument : command) {
    names_session = names_session || argument.find("{session}") != std::string::npos ||
                    argument.find("{name}") != std::string::npos;
  }
  if (!names_session) {
    throw OptionsError(
        "HandOff.command names no session; must contain \"{session}\" or \"{name}\"");
  }
  if (!std::isfinite(timeout_s) || timeout_s <= 0) {
    throw OptionsError("HandOff.timeout_s = " + std::to_string(timeout_s) +
                       "; must be a positive number of seconds");
  }
}

std::vector<std::string> HandOffCommand(const HandOff& hand_off,
                                        const std::filesystem::path& session_dir,
                                        const std::string& name) {
  std::vector<std::string> argv = hand_off.command;
  const std::string session = std::filesystem::absolute(session_dir).lexically_normal().string();
  for (std::string& argument : argv) argument = Substitute(argument, session, name);
  return argv;
}

std::string RunHandOff(const HandOff& hand_off, const std::filesystem::path& session_dir,
                       const std::string& name, const std::atomic<bool>* stop) {
  const std::vector<std::string> argv = HandOffCommand(hand_off, session_dir, name);
  if (argv.empty()) throw Error("RunHandOff: no command configured");
  ProcessOptions options;
  options.own_group = true;
  options.timeout_s = hand_off.timeout_s;
  options.stop = stop;
  options.grace_s = kHandOffGraceS;
  options.keep_bytes = 8192;  // the log shows the last line; a chatty command must not grow us
  const ProcessResult run = RunProcess(argv, options);
  std::string line;
  if (run.ended == ProcessResult::Ended::kNo) {
    line = "session " + name + " handed off: " + ShellQuoted(argv) + " exited " +
           std::to_string(run.exit_status);
    if (run.exit_status != 0) line += ": " + LastLine(run.err.empty() ? run.out : run.err);
  } else {
    const std::string why =
        run.ended == ProcessResult::Ended::kStopped
            ? "was ended because the daemon is stopping"
            : "timed out after " + Seconds(hand_off.timeout_s) + ", so it was ended";
    line = "session " + name + " hand-off " + why + ": " + ShellQuoted(argv) + " (exit status " +
           std::to_string(run.exit_status) + "); run it again by hand";
  }
  if (run.leftovers > 0) {
    line += "; ended " + std::to_string(run.leftovers) +
            " process(es) it left running in its process group";
  }
  return line;
}

}  // namespace brdfrig::acquire
