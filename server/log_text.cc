#include "log_text.h"

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"

namespace aperture {

std::string LogText(absl::string_view text, size_t max_chars) {
  std::string out;
  size_t used = 0;
  for (; used < text.size(); ++used) {
    const unsigned char c = static_cast<unsigned char>(text[used]);
    std::string piece;
    if (c == '\n')
      piece = "\\n";
    else if (c == '\r')
      piece = "\\r";
    else if (c == '\t')
      piece = "\\t";
    else if (c == '\\' || c == '\'' || c == '"')
      piece = absl::StrCat("\\", std::string(1, static_cast<char>(c)));
    else if (c < 0x20 || c >= 0x7f)
      piece = absl::StrFormat("\\x%02x", c);
    else
      piece = std::string(1, static_cast<char>(c));
    if (out.size() + piece.size() > max_chars) break;
    out += piece;
  }
  if (used < text.size()) absl::StrAppend(&out, "...(", text.size() - used, " more bytes)");
  return out;
}

}  // namespace aperture
