#include "reconstruct/raw_photo.h"

#include <libraw/libraw.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <memory>
#include <opencv2/imgproc.hpp>
#include <string>

#include "common/error.h"

namespace brdfrig::reconstruct {

bool IsRawPhoto(const std::filesystem::path& path) {
  static constexpr std::array<const char*, 13> kExtensions = {
      ".nef", ".nrw", ".cr2", ".cr3", ".crw", ".arw", ".srf",
      ".sr2", ".dng", ".raf", ".orf", ".rw2", ".pef"};
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return std::find(kExtensions.begin(), kExtensions.end(), ext) != kExtensions.end();
}

cv::Mat ReadRawPhoto(const std::filesystem::path& path) {
  // LibRaw's state is large (hundreds of KB): on the heap, one decoder per call.
  auto raw = std::make_unique<LibRaw>();
  const auto check = [&](int code, const char* step) {
    if (code != LIBRAW_SUCCESS) {
      throw FileError(path.string(), std::string("cannot decode RAW photo (") + step +
                                         "): " + libraw_strerror(code));
    }
  };
  check(raw->open_file(path.c_str()), "open");
  libraw_output_params_t& params = raw->imgdata.params;
  params.output_bps = 16;
  params.gamm[0] = 1.0;  // linear output: the HDR merge needs values proportional to exposure
  params.gamm[1] = 1.0;
  params.no_auto_bright = 1;
  // LibRaw otherwise takes a frame's own maximum as the white level when it exceeds 75 % of
  // the real one, scaling bright frames up (up to a third): values must stay proportional to
  // exposure across a bracket.
  params.adjust_maximum_thr = 0;
  params.use_camera_wb = 1;
  params.user_flip = 0;  // keep the sensor's pixel grid (the intrinsics are for it)
  check(raw->unpack(), "unpack");
  check(raw->dcraw_process(), "process");
  int code = LIBRAW_SUCCESS;
  std::unique_ptr<libraw_processed_image_t, void (*)(libraw_processed_image_t*)> image(
      raw->dcraw_make_mem_image(&code),
      [](libraw_processed_image_t* p) { LibRaw::dcraw_clear_mem(p); });
  check(code, "convert");
  if (!image || image->type != LIBRAW_IMAGE_BITMAP || image->colors != 3 || image->bits != 16) {
    throw FileError(path.string(), "RAW photo did not decode to a 16-bit RGB image");
  }
  const cv::Mat rgb(image->height, image->width, CV_16UC3, image->data);
  cv::Mat bgr;
  cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);  // copies out of LibRaw's buffer
  return bgr;
}

}  // namespace brdfrig::reconstruct
