// Offline reprocessing: many captures at once, up-to-date ones skipped, the same inputs giving
// the same material.json, and never a byte written into a capture.
#include "reconstruct/batch.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "common/atomic_file.h"
#include "common/sha256.h"
#include "tests/reconstruct/capture_fixture.h"

namespace brdfrig::reconstruct {
namespace {

namespace fs = std::filesystem;

// Hash of every file under `dir` (names and contents), to prove nothing in it changed.
std::string TreeHash(const fs::path& dir) {
  std::vector<fs::path> files;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (e.is_regular_file()) files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  Sha256 hash;
  for (const fs::path& f : files) {
    hash.Update(f.string());
    hash.UpdateFile(f);
  }
  return hash.HexDigest();
}

class BatchTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / "brdfrig_batch_test";
    fs::remove_all(root_);
    testing::SceneSpec spec;
    spec.brdf = "{model: ggx, alpha: 0.1, f0: 0.8, diffuse: 0.1}";
    spec.width = 320;
    spec.height = 240;
    spec.supersampling = 2;
    spec.positions = "[{camera_arm: 25, light_arm: -25}, {camera_arm: 45, light_arm: -45}]";
    fs::create_directories(root_ / "captures");
    for (const char* name : {"a", "b"}) {
      testing::SimulateCapture(root_ / "work" / name, spec);
      fs::rename(root_ / "work" / name / "capture", root_ / "captures" / name);
    }
  }
  // The batch's bookkeeping is under test here, not the ladder (pipeline_test and
  // reconstruct_cli_test fit every rung): one rung keeps five reconstructions quick.
  static BatchOptions OneRung() {
    BatchOptions options;
    options.reconstruct.model = "ggx";
    return options;
  }
  fs::path root_;
};

TEST_F(BatchTest, ReconstructsEveryCaptureSkipsUpToDateOnesAndIsDeterministic) {
  const std::string before = TreeHash(root_ / "captures");
  BatchOptions options = OneRung();
  options.inputs = {root_ / "captures"};
  options.output = root_ / "fits";
  options.jobs = 2;
  std::vector<BatchItem> items = ReconstructBatch(options);
  ASSERT_EQ(items.size(), 2u);
  for (const BatchItem& item : items) {
    EXPECT_EQ(item.status, BatchItem::Status::kDone) << item.message;
  }
  const std::string first = ReadFileToString(root_ / "fits" / "a" / "material.json");

  items = ReconstructBatch(options);  // nothing changed: nothing redone
  for (const BatchItem& item : items) EXPECT_EQ(item.status, BatchItem::Status::kUpToDate);

  options.force = true;  // redone: the same bytes
  items = ReconstructBatch(options);
  for (const BatchItem& item : items) EXPECT_EQ(item.status, BatchItem::Status::kDone);
  EXPECT_EQ(ReadFileToString(root_ / "fits" / "a" / "material.json"), first);
  EXPECT_EQ(TreeHash(root_ / "captures"), before);
}

TEST_F(BatchTest, RefusesToWriteInsideACaptureButNotBesideIt) {
  const std::string before = TreeHash(root_ / "captures" / "a");
  BatchOptions options = OneRung();
  options.inputs = {root_ / "captures" / "a"};
  options.output = root_ / "captures" / "a" / "fit" / "material.json";
  std::vector<BatchItem> items = ReconstructBatch(options);
  ASSERT_EQ(items.size(), 1u);
  EXPECT_EQ(items[0].status, BatchItem::Status::kFailed);
  EXPECT_NE(items[0].message.find("lies inside the capture"), std::string::npos)
      << items[0].message;
  EXPECT_EQ(TreeHash(root_ / "captures" / "a"), before);
  // A sibling whose name starts with the capture's is not inside it.
  options.output = root_ / "captures" / "a2" / "material.json";
  items = ReconstructBatch(options);
  EXPECT_EQ(items[0].status, BatchItem::Status::kDone) << items[0].message;
}

}  // namespace
}  // namespace brdfrig::reconstruct
