#include "batch/array_spec.h"

#include <algorithm>
#include <sstream>

#include "common/error.h"

namespace brdfrig::batch {

std::string ArraySpec(std::vector<int> indices, int throttle) {
  if (indices.empty()) throw Error("an array of no tasks cannot be submitted");
  std::sort(indices.begin(), indices.end());
  indices.erase(std::unique(indices.begin(), indices.end()), indices.end());
  std::string spec;
  for (std::size_t i = 0; i < indices.size();) {
    std::size_t j = i;
    while (j + 1 < indices.size() && indices[j + 1] == indices[j] + 1) ++j;
    if (!spec.empty()) spec += ",";
    spec += std::to_string(indices[i]);
    if (j > i) spec += "-" + std::to_string(indices[j]);
    i = j + 1;
  }
  if (throttle > 0) spec += "%" + std::to_string(throttle);
  return spec;
}

std::vector<int> ExpandArraySpec(const std::string& spec) {
  std::string list = spec;
  if (!list.empty() && list.front() == '[') list.erase(0, 1);
  if (!list.empty() && list.back() == ']') list.pop_back();
  if (const std::size_t percent = list.find('%'); percent != std::string::npos) {
    list.resize(percent);
  }
  const auto bad = [&] { return Error("\"" + spec + "\" is not a job-array index list"); };
  std::vector<int> indices;
  std::istringstream parts(list);
  std::string part;
  while (std::getline(parts, part, ',')) {
    int first = 0, last = 0;
    char dash = 0;
    std::istringstream range(part);
    if (!(range >> first) || first < 0) throw bad();
    last = first;
    if (range >> dash) {
      if (dash != '-' || !(range >> last) || last < first) throw bad();
    }
    if (range >> dash) throw bad();  // anything after the range ("1-5:2" steps are not ours)
    for (int i = first; i <= last; ++i) indices.push_back(i);
  }
  if (indices.empty()) throw bad();
  std::sort(indices.begin(), indices.end());
  indices.erase(std::unique(indices.begin(), indices.end()), indices.end());
  return indices;
}

}  // namespace brdfrig::batch
