// Lets `--max-queue` mean `--max_queue`: absl flags spell names with underscores, most command
// lines' style uses dashes. Only the name part before '=' is rewritten.
#pragma once

#include <string>
#include <vector>

namespace aperture {

class DashedFlagNames {
 public:
  DashedFlagNames(int argc, char** argv);
  int argc() const { return static_cast<int>(pointers_.size()); }
  char** argv() { return pointers_.data(); }

 private:
  std::vector<std::string> args_;
  std::vector<char*> pointers_;
};

}  // namespace aperture
