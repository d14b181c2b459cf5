// Base64 (RFC 4648, with padding) for binary arrays inside JSON files (a material's table).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace brdfrig {

std::string Base64Encode(const std::vector<std::uint8_t>& bytes);
// nullopt when `text` is not padded base64.
std::optional<std::vector<std::uint8_t>> Base64Decode(std::string_view text);

}  // namespace brdfrig
