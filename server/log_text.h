// Client-supplied text made safe for one log line: control characters and
// quotes escaped (a newline in a scene name cannot forge a log line), bytes outside printable
// ASCII as \xNN, and the whole cut to `max_chars` with a count of what was cut.
#pragma once

#include <cstddef>
#include <string>

#include "absl/strings/string_view.h"

namespace aperture {

std::string LogText(absl::string_view text, size_t max_chars = 200);

}  // namespace aperture
