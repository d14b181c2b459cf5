// Checking options in Validate() methods. The message names the field, its value and the rule,
// in Ceres' style:
//
//   SliceFitOptions.max_iterations = 0; must be >= 1
//
// Fields are named as in code (Struct.field); apps/ maps them to its flags where it has to.
#pragma once

#include <sstream>
#include <string>
#include <string_view>

#include "common/error.h"

namespace brdfrig {

// Throws OptionsError "<field> = <value>; must be <rule>" unless `ok`.
template <typename T>
void CheckOption(bool ok, std::string_view field, const T& value, std::string_view rule) {
  if (ok) return;
  std::ostringstream message;
  message << field << " = " << value << "; must be " << rule;
  throw OptionsError(message.str());
}

}  // namespace brdfrig
