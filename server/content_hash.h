// SHA-256 of texture content: the key of the texture store and of uploads (lowercase hex).
#pragma once

#include <string>
#include <string_view>

namespace aperture {

std::string Sha256Hex(std::string_view bytes);

// 64 lowercase hex digits.
bool IsSha256Hex(std::string_view text);

}  // namespace aperture
