// Offline reprocessing: `brdfrig reconstruct` over one capture or many (a directory of
// captures), in parallel, skipping captures whose material.json is up to date (same software
// version, same photo contents by SHA-256, and the same options that change the result:
// ReconstructOptions::ResultKey), never writing into a capture's own directory.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "reconstruct/pipeline.h"

namespace brdfrig::reconstruct {

struct BatchOptions {
  std::vector<std::filesystem::path> inputs;  // captures, or directories holding captures
  // One capture: the material file (…/material.json) or a directory; several: a directory
  // receiving <capture name>/material.json, hdr/ and report.txt.
  std::filesystem::path output;
  ReconstructOptions reconstruct;
  int jobs = 2;        // captures reconstructed at once
  bool force = false;  // redo even when up to date
  void Validate() const;
};

struct BatchItem {
  std::filesystem::path input, material_file;
  enum class Status { kDone, kUpToDate, kFailed } status = Status::kFailed;
  std::string message;  // failure reason, or the result's one-line summary
  std::string ladder;   // done: every rung's scores (LadderResult::Summary), for the terminal
  // The material (done or up to date) lacks these positions: "p03: <reason>". Empty when
  // every captured position was used.
  std::vector<std::string> dropped;
  // The material used these positions although their photos were damaged (NaN/Inf pixels):
  // "p03: <reason>". Like a dropped position, this makes the item partial.
  std::vector<std::string> degraded;
  bool Partial() const { return !dropped.empty() || !degraded.empty(); }
  double seconds = 0;
  // "done", "partial" (a material written without some positions), "up to date", "FAILED"
  std::string StatusName() const;
};

// The exit status of `brdfrig reconstruct` for these items: 0 every capture complete, 3 every
// material written but some positions dropped or degraded, 1 some capture failed (nothing
// written for it).
int BatchExitStatus(const std::vector<BatchItem>& items);

// Whether `dir` is a capture this command can read (a `brdfrig simulate` output or a session).
bool IsCaptureDirectory(const std::filesystem::path& dir);

// Reads a capture of either kind.
CaptureSet LoadCapture(const std::filesystem::path& dir);

// SHA-256 over the capture's photo files (names and contents), hex.
std::string CaptureFingerprint(const CaptureSet& capture);

// The captures `options.inputs` name (directories of captures expanded, sorted), each with the
// material file it gets; nothing is read or written yet. Throws FileError for an input that is
// neither a capture nor a directory of captures.
std::vector<BatchItem> ListBatchItems(const BatchOptions& options);

// Whether ProcessBatchItem would reconstruct `item` (false: its material is up to date — same
// software, same photos, same ResultKey of the options — and, under strict, complete). Hashes the
// capture's photos.
bool NeedsReconstruct(const BatchItem& item, const BatchOptions& options);

// One item of a batch: skipped when up to date, else reconstructed into
// item.material_file's directory (material.json written atomically, last). Sets status,
// message, dropped, ladder and seconds; a failure is recorded in the item, not thrown.
void ProcessBatchItem(const BatchOptions& options, BatchItem& item,
                      const ProgressCallback& progress = {});

// Every item of ListBatchItems through ProcessBatchItem, options.jobs at a time.
std::vector<BatchItem> ReconstructBatch(const BatchOptions& options,
                                        const ProgressCallback& progress = {});

}  // namespace brdfrig::reconstruct
