// Issue 25: nothing a user writes or a disk does loses a material or stops a batch. A material
// nested too deep in the output tree is redone, not a crash; an output path that is a file is
// that capture's error; a failed write is an error of the run, never a dropped position; two
// captures of one name are refused before any work.
#include <gtest/gtest.h>

#include <fstream>

#include "common/atomic_file.h"
#include "common/error.h"
#include "reconstruct/batch.h"
#include "tests/reconstruct/capture_fixture.h"

namespace brdfrig::reconstruct {
namespace {

namespace fs = std::filesystem;

class OutputSafetyTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = new fs::path(fs::temp_directory_path() / "brdfrig_output_safety");
    fs::remove_all(*root_);
    testing::SceneSpec spec;
    spec.width = 320;
    spec.height = 240;
    spec.supersampling = 2;
    spec.positions =
        "[{camera_arm: 20, light_arm: -20}, {camera_arm: 35, light_arm: -35}, "
        "{camera_arm: 50, light_arm: -50}]";
    const brdf::Material truth = testing::FlatSliceTruth();
    fs::create_directories(*root_ / "arch");
    for (const char* name : {"c1", "c2"}) {
      (void)testing::SimulateCapture(*root_ / "work" / name, spec, &truth);
      fs::rename(*root_ / "work" / name / "capture", *root_ / "arch" / name);
    }
  }
  static void TearDownTestSuite() { delete root_; }

  static BatchOptions Options(std::vector<fs::path> inputs, const fs::path& output) {
    BatchOptions options;
    options.inputs = std::move(inputs);
    options.output = output;
    options.jobs = 2;
    options.reconstruct.model = "seed";
    return options;
  }

  static fs::path Fresh(const std::string& name) {
    const fs::path dir = *root_ / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
  }

  static fs::path* root_;
};
fs::path* OutputSafetyTest::root_ = nullptr;

// Finding 5: a material.json nested 200,000 arrays deep in the output tree crashed the whole
// `reconstruct -j 2` (exit 139, no capture processed); it is unreadable, so it is redone.
TEST_F(OutputSafetyTest, TooDeepMaterialInTheOutputTreeIsRedoneNotACrash) {
  const fs::path fits = Fresh("deep");
  fs::create_directories(fits / "c1");
  std::ofstream(fits / "c1" / "material.json")
      << "{\"version\": 2, \"format\": " << std::string(200000, '[') << std::string(200000, ']')
      << "}";
  try {
    (void)brdf::ReadMaterialFile(fits / "c1" / "material.json");
    FAIL() << "a 200,000 deep material was read";
  } catch (const FileError& e) {
    EXPECT_EQ(e.file(), (fits / "c1" / "material.json").string());
  }
  const std::vector<BatchItem> items = ReconstructBatch(Options({*root_ / "arch"}, fits));
  ASSERT_EQ(items.size(), 2u);
  for (const BatchItem& item : items) {
    EXPECT_EQ(item.status, BatchItem::Status::kDone) << item.input << ": " << item.message;
  }
  EXPECT_EQ(BatchExitStatus(items), 0);
  EXPECT_NO_THROW((void)brdf::ReadMaterialFile(fits / "c1" / "material.json"));
}

// Finding 5: `fits/c2` a regular file aborted `reconstruct arch -o fits -j 2` with an uncaught
// std::filesystem::filesystem_error (exit 134) and c1 was not processed.
TEST_F(OutputSafetyTest, OutputPathThatIsAFileIsThatCapturesErrorTheOthersAreDone) {
  const fs::path fits = Fresh("file_in_the_way");
  std::ofstream(fits / "c2") << "a file where c2's directory goes";
  for (const int jobs : {2, 1}) {
    BatchOptions options = Options({*root_ / "arch"}, fits);
    options.jobs = jobs;
    options.force = true;
    const std::vector<BatchItem> items = ReconstructBatch(options);
    ASSERT_EQ(items.size(), 2u);
    EXPECT_EQ(items[0].status, BatchItem::Status::kDone) << items[0].message;
    EXPECT_EQ(items[1].status, BatchItem::Status::kFailed);
    EXPECT_NE(items[1].message.find((fits / "c2").string()), std::string::npos) << items[1].message;
    EXPECT_EQ(BatchExitStatus(items), 1);
  }
}

// Finding 1: on a full disk the positions whose HDR files failed to write were dropped and a
// material fitted from the rest replaced the good one (exit 3). A failed write is an error of
// the run: exit 1, the previous material untouched. The write is made to fail for any user,
// root included, by a non-empty directory where hdr/p01.exr is renamed into place.
TEST_F(OutputSafetyTest, AFailedHdrWriteFailsTheRunAndKeepsThePreviousMaterial) {
  const fs::path out = Fresh("hdr_write_fails");
  BatchOptions options = Options({*root_ / "arch" / "c1"}, out / "material.json");
  ASSERT_EQ(BatchExitStatus(ReconstructBatch(options)), 0);
  const std::string good = ReadFileToString(out / "material.json");
  fs::remove(out / "hdr" / "p01.exr");
  fs::create_directories(out / "hdr" / "p01.exr" / "in_the_way");
  options.force = true;
  const std::vector<BatchItem> items = ReconstructBatch(options);
  ASSERT_EQ(items.size(), 1u);
  EXPECT_EQ(items[0].status, BatchItem::Status::kFailed) << items[0].message;
  EXPECT_NE(items[0].message.find("p01.exr"), std::string::npos) << items[0].message;
  EXPECT_TRUE(items[0].dropped.empty());
  EXPECT_EQ(BatchExitStatus(items), 1);
  EXPECT_EQ(ReadFileToString(out / "material.json"), good);
}

// Finding 2: archX/tile and archY/tile in one `reconstruct archX archY -o fits` both went to
// fits/tile: both "done", one material lost. The clash is refused before any work.
TEST_F(OutputSafetyTest, TwoCapturesOfOneNameAreRefusedBeforeAnyWork) {
  const fs::path other = Fresh("other");
  fs::copy(*root_ / "arch" / "c1", other / "c1", fs::copy_options::recursive);
  const fs::path fits = *root_ / "clash_fits";
  fs::remove_all(fits);
  try {
    (void)ReconstructBatch(Options({*root_ / "arch", other}, fits));
    FAIL() << "two captures named c1 were both reconstructed into " << fits;
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find((*root_ / "arch" / "c1").string()), std::string::npos) << message;
    EXPECT_NE(message.find((other / "c1").string()), std::string::npos) << message;
  }
  EXPECT_FALSE(fs::exists(fits));
}

}  // namespace
}  // namespace brdfrig::reconstruct
