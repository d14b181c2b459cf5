// The libgphoto2 backend against libgphoto2's own "Directory Browse" driver (port disk:DIR),
// which serves a directory as a camera's storage: the real library, camlib loading, port
// lookup, file listing and download run; only capture is missing, and that must be a clear
// error.
#include "rig/gphoto2_camera.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "rig/backend_registry.h"
#include "rig/gphoto2_errors.h"
#include "rig/hardware_backends.h"

// libgphoto2 keeps state until process exit (libltdl handles of its camlibs, the USB port
// library's device lists); LeakSanitizer reports it in asan builds although it is neither ours
// nor growing per call. Only allocations made inside those libraries are suppressed. Their
// stacks pass through code built without frame pointers, so the suppression can only match
// with the slow (DWARF) unwinder on malloc.
extern "C" const char* __lsan_default_suppressions() {
  return "leak:libgphoto2.so\nleak:libgphoto2_port.so\nleak:libltdl.so\n";
}
extern "C" const char* __asan_default_options() { return "fast_unwind_on_malloc=0"; }

namespace brdfrig::rig {
namespace {

class Gphoto2CameraTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("brdfrig_gphoto2_test_" + std::to_string(getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_ / "sub");
    content_ = "not really a JPEG, but bytes to compare\n";
    std::ofstream(dir_ / "IMG_0001.JPG", std::ios::binary) << content_;
    std::ofstream(dir_ / "sub" / "IMG_0002.CR2", std::ios::binary) << "raw";
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  Gphoto2Options DirectoryCamera() const {
    Gphoto2Options options;
    options.model = "Directory Browse";
    options.port = "disk:" + dir_.string();
    options.operation_timeout = std::chrono::milliseconds(5000);
    options.event_drain = std::chrono::milliseconds(100);
    return options;
  }

  std::filesystem::path dir_;
  std::string content_;
};

TEST_F(Gphoto2CameraTest, OpensTheDirectoryDriverAndReportsModelAndPort) {
  Gphoto2Camera camera(DirectoryCamera());
  const CameraInfo info = camera.Info();
  EXPECT_EQ(info.model, "Directory Browse");
  EXPECT_EQ(info.port, "disk:" + dir_.string());
}

TEST_F(Gphoto2CameraTest, ListsFilesRecursivelyAndDownloadsOneToMemoryAndToAnFd) {
  Gphoto2Camera camera(DirectoryCamera());
  const std::vector<CameraFileRef> files = camera.ListFiles("/");
  const auto find = [&](const std::string& name) {
    return std::find_if(files.begin(), files.end(),
                        [&](const CameraFileRef& f) { return f.name == name; });
  };
  ASSERT_NE(find("IMG_0001.JPG"), files.end());
  ASSERT_NE(find("IMG_0002.CR2"), files.end());
  EXPECT_EQ(find("IMG_0002.CR2")->folder, "/sub");

  const Frame frame = camera.Download(*find("IMG_0001.JPG"));
  EXPECT_EQ(frame.file_name, "IMG_0001.JPG");
  ASSERT_EQ(frame.bytes.size(), content_.size());
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(frame.bytes.data()), frame.bytes.size()),
            content_);

  const std::filesystem::path out = dir_.string() + "_out.jpg";
  const int fd = open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  ASSERT_NE(fd, -1);
  EXPECT_EQ(camera.DownloadToFd(*find("IMG_0001.JPG"), fd), content_.size());
  EXPECT_NE(fcntl(fd, F_GETFD), -1);  // the caller's descriptor stays open
  close(fd);
  EXPECT_EQ(std::filesystem::file_size(out), content_.size());
  std::filesystem::remove(out);
}

TEST_F(Gphoto2CameraTest, CaptureOnACameraThatCannotCaptureIsAClearUnsupportedError) {
  Gphoto2Camera camera(DirectoryCamera());
  try {
    camera.Capture();
    FAIL() << "the directory driver captured";
  } catch (const CameraError& e) {
    EXPECT_EQ(e.kind(), CameraError::Kind::kUnsupported) << e.what();
    EXPECT_LT(e.code(), 0);
    EXPECT_NE(std::string(e.what()).find("cannot capture"), std::string::npos) << e.what();
    EXPECT_FALSE(e.recoverable());
  }
}

TEST_F(Gphoto2CameraTest, ExposureOnACameraWithoutShutterSpeedsIsUnsupported) {
  Gphoto2Camera camera(DirectoryCamera());
  try {
    camera.SetExposure(1.0 / 60);
    FAIL();
  } catch (const CameraError& e) {
    EXPECT_EQ(e.kind(), CameraError::Kind::kUnsupported) << e.what();
  }
}

TEST_F(Gphoto2CameraTest, UnknownModelAndUnknownPortAreNotFound) {
  Gphoto2Options options = DirectoryCamera();
  options.model = "Nikon DSC D99999";
  try {
    Gphoto2Camera camera(options);
    FAIL();
  } catch (const CameraError& e) {
    EXPECT_EQ(e.kind(), CameraError::Kind::kNotFound) << e.what();
  }
  options = DirectoryCamera();
  options.port.clear();
  options.model = "Canon EOS 5D Mark IV";
  try {
    Gphoto2Camera camera(options);  // autodetect finds no such camera here
    FAIL();
  } catch (const CameraError& e) {
    EXPECT_EQ(e.kind(), CameraError::Kind::kNotFound) << e.what();
    EXPECT_NE(std::string(e.what()).find("gvfs"), std::string::npos) << e.what();
  }
}

TEST_F(Gphoto2CameraTest, WatchdogCancelsThroughTheContextAsATimeoutAndTheCameraStaysUsable) {
  Gphoto2Camera camera(DirectoryCamera());
  camera.set_operation_timeout(std::chrono::milliseconds(0));  // already expired
  try {
    camera.ListFiles("/");
    FAIL() << "listing was not cancelled";
  } catch (const CameraError& e) {
    EXPECT_EQ(e.kind(), CameraError::Kind::kTimeout) << e.what();
    EXPECT_NE(std::string(e.what()).find("cancelled"), std::string::npos) << e.what();
    EXPECT_TRUE(e.recoverable());
  }
  camera.set_operation_timeout(std::chrono::milliseconds(5000));
  EXPECT_EQ(camera.ListFiles("/").size(), 2u);
}

TEST(Gphoto2ErrorsTest, ClaimedUsbNamesGvfsAndBusyIsRecoverable) {
  const CameraError claimed = Gphoto2Error(-53, "opening the camera");
  EXPECT_EQ(claimed.kind(), CameraError::Kind::kClaimed);
  EXPECT_NE(std::string(claimed.what()).find("gvfs-gphoto2-volume-monitor"), std::string::npos);
  EXPECT_NE(std::string(claimed.what()).find("gvfsd-gphoto2"), std::string::npos);
  EXPECT_TRUE(Gphoto2Error(-110, "capture").recoverable());  // busy
  EXPECT_EQ(Gphoto2Error(-115, "capture").kind(), CameraError::Kind::kStorageFull);
  EXPECT_EQ(Gphoto2Error(-52, "capture").kind(), CameraError::Kind::kGone);
  EXPECT_EQ(Gphoto2Error(-10, "capture").kind(), CameraError::Kind::kTimeout);
}

TEST(Gphoto2SettingsTest, RigYamlCameraSettingsAreCheckedWithFileAndLine) {
  RegisterHardwareBackends();
  const YamlNode settings =
      LoadYamlString("model: Directory Browse\ncapture_target: sd\n", "rig.yaml");
  try {
    CreateCamera("gphoto2", settings, {"camera", "/tmp"});
    FAIL();
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("rig.yaml:2:"), std::string::npos) << e.what();
  }
  const YamlNode typo = LoadYamlString("model: Directory Browse\nshutter: 1\n", "rig.yaml");
  EXPECT_THROW(CreateCamera("gphoto2", typo, {"camera", "/tmp"}), FileError);
}

}  // namespace
}  // namespace brdfrig::rig
