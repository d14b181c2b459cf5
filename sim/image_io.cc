#include "sim/image_io.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStdIO.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>

#include "common/atomic_file.h"
#include "sim/simulator.h"

namespace brdfrig::sim {
namespace {

void InsertChannels(Imf::FrameBuffer* fb, char* base, std::size_t row_bytes) {
  const std::size_t px = 3 * sizeof(float);
  // OpenCV stores B, G, R: R is the third float of a pixel.
  fb->insert("R", Imf::Slice(Imf::FLOAT, base + 2 * sizeof(float), px, row_bytes));
  fb->insert("G", Imf::Slice(Imf::FLOAT, base + 1 * sizeof(float), px, row_bytes));
  fb->insert("B", Imf::Slice(Imf::FLOAT, base, px, row_bytes));
}

}  // namespace

std::vector<std::byte> EncodePhoto(const cv::Mat& sensor_image, const SensorDescription& sensor) {
  CV_Assert(sensor_image.type() == CV_32FC3);
  const bool eight_bit = sensor.format == PhotoFormat::kJpeg8;
  const double levels = eight_bit ? 255.0 : 65535.0;
  cv::Mat codes(sensor_image.size(), eight_bit ? CV_8UC3 : CV_16UC3);
  for (int y = 0; y < sensor_image.rows; ++y) {
    const float* in = sensor_image.ptr<float>(y);
    for (int i = 0; i < sensor_image.cols * 3; ++i) {
      const double code = std::round(std::clamp(static_cast<double>(in[i]), 0.0, 1.0) * levels);
      if (eight_bit) {
        codes.ptr<std::uint8_t>(y)[i] = static_cast<std::uint8_t>(code);
      } else {
        codes.ptr<std::uint16_t>(y)[i] = static_cast<std::uint16_t>(code);
      }
    }
  }
  std::vector<int> params;
  if (eight_bit) params = {cv::IMWRITE_JPEG_QUALITY, sensor.jpeg_quality};
  if (sensor.format == PhotoFormat::kPng16) params = {cv::IMWRITE_PNG_COMPRESSION, 1};
  std::vector<std::uint8_t> buffer;
  if (!cv::imencode(sensor.Extension(), codes, buffer, params)) {
    throw Error("could not encode a " + sensor.Extension() + " image");
  }
  std::vector<std::byte> bytes(buffer.size());
  std::transform(buffer.begin(), buffer.end(), bytes.begin(),
                 [](std::uint8_t b) { return static_cast<std::byte>(b); });
  return bytes;
}

void WriteRadianceExr(const std::filesystem::path& path, const cv::Mat& radiance) {
  CV_Assert(radiance.type() == CV_32FC3 && radiance.isContinuous());
  Imf::Header header(radiance.cols, radiance.rows);
  header.compression() = Imf::ZIP_COMPRESSION;
  for (const char* name : {"R", "G", "B"}) header.channels().insert(name, Imf::Channel(Imf::FLOAT));
  Imf::StdOSStream stream;
  try {
    Imf::OutputFile file(stream, header);
    Imf::FrameBuffer fb;
    InsertChannels(&fb, const_cast<char*>(reinterpret_cast<const char*>(radiance.data)),
                   radiance.step[0]);
    file.setFrameBuffer(fb);
    file.writePixels(radiance.rows);
  } catch (const std::exception& e) {
    throw Error(path.string() + ": cannot encode EXR: " + e.what());
  }
  WriteFileAtomically(path, stream.str());
}

cv::Mat ReadRadianceExr(const std::filesystem::path& path) {
  try {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i window = file.header().dataWindow();
    const int width = window.max.x - window.min.x + 1;
    const int height = window.max.y - window.min.y + 1;
    cv::Mat image(height, width, CV_32FC3, cv::Scalar::all(0));
    char* origin = reinterpret_cast<char*>(image.data) -
                   (static_cast<std::ptrdiff_t>(window.min.y) * image.step[0]) -
                   static_cast<std::ptrdiff_t>(window.min.x) * 3 * sizeof(float);
    Imf::FrameBuffer fb;
    InsertChannels(&fb, origin, image.step[0]);
    file.setFrameBuffer(fb);
    file.readPixels(window.min.y, window.max.y);
    return image;
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw FileError(path.string(), std::string("cannot read EXR: ") + e.what());
  }
}

void WriteTrueGeometry(const std::filesystem::path& path, const TrueGeometry& geometry) {
  WriteFileAtomically(path, geometry.ToJson().dump(2) + "\n");
}

}  // namespace brdfrig::sim
