// Runs a command line through the shell and collects its exit code and its stdout and stderr.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace aperture::testing {

struct ProcessResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

inline ProcessResult RunProcess(const std::string& command_line) {
  ProcessResult r;
  FILE* pipe = popen((command_line + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return r;
  std::array<char, 4096> buffer;
  while (fgets(buffer.data(), buffer.size(), pipe) != nullptr) r.output += buffer.data();
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

}  // namespace aperture::testing
