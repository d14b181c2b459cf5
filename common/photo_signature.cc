#include "common/photo_signature.h"

#include <array>
#include <cstdint>

namespace brdfrig {

bool HasPhotoSignature(std::span<const std::byte> head) {
  const auto starts = [&](std::initializer_list<std::uint8_t> magic) {
    if (head.size() < magic.size()) return false;
    std::size_t i = 0;
    for (const std::uint8_t b : magic) {
      if (head[i++] != static_cast<std::byte>(b)) return false;
    }
    return true;
  };
  return starts({0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'}) ||  // PNG
         starts({0xFF, 0xD8, 0xFF}) ||                             // JPEG
         starts({'I', 'I', 42, 0}) || starts({'M', 'M', 0, 42});   // TIFF, little/big endian
}

}  // namespace brdfrig
