// Fault injection for the acquisition's crash and fault tests, compiled in but inert unless
// switched on (environment variables for a child process, setters for in-process tests).
//
//   BRDFRIG_TEST_KILL_AT=N        the process SIGKILLs itself at the N-th instrumented point
//   BRDFRIG_TEST_KILL_LOG=FILE    ... after appending that point's phase name to FILE
//   BRDFRIG_TEST_FAIL_WRITE_AT=N  the N-th frame file write fails with "No space left on device"
//
// Instrumented points are the moments a crash is interesting: before/after a move, before a
// shot (exposing), after the download, after the temporary file is written, after the rename,
// inside the recording transaction and after its commit.
#pragma once

namespace brdfrig::acquire::test_hooks {

// Phases named by KillPoint (also written to the kill log).
inline constexpr const char* kMoving = "moving";
inline constexpr const char* kExposing = "exposing";
inline constexpr const char* kDownloading = "downloading";
inline constexpr const char* kWriting = "writing";
inline constexpr const char* kRecording = "recording";

// Counts one instrumented point; kills the process when it is the chosen one.
void KillPoint(const char* phase);

// Throws brdfrig::Error (ENOSPC) when this is the chosen frame write.
void BeforeFrameWrite();

// In-process control for tests: 0 switches the injection off.
void SetFailWriteAt(int n);

}  // namespace brdfrig::acquire::test_hooks
