// The software version written into sessions and material files (provenance): one place.
#pragma once

namespace brdfrig {

inline constexpr const char* kSoftwareVersion = "0.1.0";  // = project(VERSION) in CMakeLists.txt

}  // namespace brdfrig
