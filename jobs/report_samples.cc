#include "jobs/report_samples.h"

#include "common/error.h"

namespace brdfrig::jobs {

std::vector<evaluate::MeasuredSample> MeasureReportSamples(
    const reconstruct::CaptureSet& capture, const reconstruct::MeasureOptions& options,
    const std::function<void(const std::string&)>& say) {
  reconstruct::MeasureOptions measure = options;
  measure.hdr_dir.clear();  // the reconstruction wrote its HDR images already
  reconstruct::MeasureState state;
  std::vector<evaluate::MeasuredSample> out;
  for (const reconstruct::CapturePosition& position : capture.positions) {
    if (position.validation) continue;
    try {
      const reconstruct::MeasuredPosition measured =
          reconstruct::MeasurePosition(position, capture.nominal, measure, &state);
      for (const reconstruct::DirectionSample& s : measured.directions.samples) {
        out.push_back({s.l, s.v, brdf::Rgb(s.f[0], s.f[1], s.f[2])});
      }
    } catch (const Error& e) {
      if (say)
        say(reconstruct::PositionName(position.index) + ": no samples for the report: " + e.what());
    }
  }
  return out;
}

}  // namespace brdfrig::jobs
