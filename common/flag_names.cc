#include "flag_names.h"

#include <algorithm>

namespace aperture {

DashedFlagNames::DashedFlagNames(int argc, char** argv) : args_(argv, argv + argc) {
  for (size_t i = 1; i < args_.size(); ++i) {
    std::string& arg = args_[i];
    if (arg.size() < 3 || arg.rfind("--", 0) != 0) continue;
    const size_t end = std::min(arg.find('='), arg.size());
    std::replace(arg.begin() + 2, arg.begin() + static_cast<std::ptrdiff_t>(end), '-', '_');
  }
  for (std::string& arg : args_) pointers_.push_back(arg.data());
}

}  // namespace aperture
