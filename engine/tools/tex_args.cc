#include "tools/tex_args.h"

#include <algorithm>
#include <cstdio>

#include "absl/strings/str_cat.h"

namespace aperture {

int Fail(const char* command, const std::string& message) {
  std::fprintf(stderr, "aperture-tex %s: %s\n", command, message.c_str());
  return 2;
}

absl::StatusOr<Args> ParseArgs(int argc, char** argv, const std::vector<std::string>& known) {
  Args args;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      args.help = true;
    } else if (a.rfind("-", 0) == 0 && a.size() > 1) {
      if (std::find(known.begin(), known.end(), a) == known.end())
        return absl::InvalidArgumentError(absl::StrCat("unknown option '", a, "'"));
      if (i + 1 >= argc) return absl::InvalidArgumentError(absl::StrCat(a, " needs a value"));
      args.options.emplace_back(a, argv[++i]);
    } else {
      args.positional.push_back(a);
    }
  }
  return args;
}

}  // namespace aperture
