#include "acquire/hand_off.h"

#include "common/error.h"
#include "common/subprocess.h"

namespace brdfrig::acquire {

namespace {

void ReplaceAll(std::string& text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos;
       at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
}

std::string LastLine(std::string text) {
  while (!text.empty() && text.back() == '\n') text.pop_back();
  const std::size_t newline = text.rfind('\n');
  return newline == std::string::npos ? text : text.substr(newline + 1);
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
}

std::vector<std::string> HandOffCommand(const HandOff& hand_off,
                                        const std::filesystem::path& session_dir,
                                        const std::string& name) {
  std::vector<std::string> argv = hand_off.command;
  const std::string session = std::filesystem::absolute(session_dir).lexically_normal().string();
  for (std::string& argument : argv) {
    ReplaceAll(argument, "{session}", session);
    ReplaceAll(argument, "{name}", name);
  }
  return argv;
}

std::string RunHandOff(const HandOff& hand_off, const std::filesystem::path& session_dir,
                       const std::string& name) {
  const std::vector<std::string> argv = HandOffCommand(hand_off, session_dir, name);
  const ProcessResult run = RunProcess(argv);
  std::string line = "session " + name + " handed off: " + ShellQuoted(argv) + " exited " +
                     std::to_string(run.exit_status);
  if (!run.ok()) line += ": " + LastLine(run.err.empty() ? run.out : run.err);
  return line;
}

}  // namespace brdfrig::acquire
