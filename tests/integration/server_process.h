// Starts a real aperture-server on a free loopback port (it is started with --listen
// 127.0.0.1:0 and reports the port it got) and kills it when the test ends, pass or fail.
#pragma once

#include <sys/types.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace aperture::testing {

class ServerProcess {
 public:
  // Empty on failure (the test then fails with the server's log in the message).
  static std::unique_ptr<ServerProcess> Start(const std::vector<std::string>& args,
                                              std::string* error);
  ~ServerProcess();  // SIGKILL if still running, then reaps it

  const std::string& address() const { return address_; }
  pid_t pid() const { return pid_; }
  void Signal(int signal) const;
  // The exit status if the process ended within `seconds`.
  std::optional<int> WaitForExit(double seconds);
  std::string Log() const;  // what it wrote to stderr so far
  // Its resident set now (VmRSS) and at its largest so far (VmHWM), MiB; -1 if unreadable.
  double ResidentMb() const;
  double PeakResidentMb() const;

 private:
  ServerProcess() = default;
  pid_t pid_ = -1;
  bool reaped_ = false;
  std::string address_, log_path_, store_path_;
};

struct CommandResult {
  int exit_code = -1;  // -1: killed at the timeout
  std::string out, err;
};

// Runs a command (no shell) with a time limit; its output is captured through files.
CommandResult RunCommand(const std::vector<std::string>& argv, double timeout_seconds);

}  // namespace aperture::testing
