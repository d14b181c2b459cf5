// daemon.yaml (`brdfrig daemon --config`): data directory, rig, socket, TCP port and token file.
#include "acquire/daemon_config.h"
#include "common/error.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // A token file the reader accepts (mode 0600), for configurations that name it.
  static const bool token_written = [] {
    const auto token = brdfrig::fuzz::WriteScratchFile("token", "0123456789abcdef\n");
    std::filesystem::permissions(
        token, std::filesystem::perms::owner_read | std::filesystem::perms::owner_write);
    return true;
  }();
  (void)token_written;
  try {
    brdfrig::acquire::LoadDaemonConfig(brdfrig::fuzz::WriteScratchFile("daemon.yaml", data, size));
  } catch (const brdfrig::Error&) {
    // The documented rejection of a malformed configuration.
  }
  return 0;
}
