#include "integration/server_process.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

namespace aperture::testing {
namespace {

std::string TempPath(const std::string& stem) {
  static std::atomic<int> counter{0};
  const char* dir = std::getenv("TMPDIR");
  return std::string(dir ? dir : "/tmp") + "/aperture_it_" + std::to_string(getpid()) + "_" +
         std::to_string(counter++) + "_" + stem;
}

std::string ReadAll(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream content;
  content << in.rdbuf();
  return content.str();
}

pid_t Spawn(const std::vector<std::string>& argv, int out_fd, int err_fd) {
  const pid_t pid = fork();
  if (pid == 0) {
    dup2(out_fd, 1);
    dup2(err_fd, 2);
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execv(args[0], args.data());
    _exit(127);
  }
  return pid;
}

std::optional<int> WaitPid(pid_t pid, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (true) {
    int status = 0;
    if (waitpid(pid, &status, WNOHANG) == pid)
      return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    if (std::chrono::steady_clock::now() > end) return std::nullopt;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

}  // namespace

std::unique_ptr<ServerProcess> ServerProcess::Start(const std::vector<std::string>& args,
                                                    std::string* error) {
  std::unique_ptr<ServerProcess> server(new ServerProcess);
  server->log_path_ = TempPath("server.log");
  int out[2];
  if (pipe(out) != 0) return nullptr;
  const int err_fd = open(server->log_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  std::vector<std::string> argv = {APERTURE_SERVER_BIN, "--listen=127.0.0.1:0"};
  argv.insert(argv.end(), args.begin(), args.end());
  // A store of its own unless the test names one: tests never touch the machine's real store.
  const bool names_store = std::any_of(
      args.begin(), args.end(), [](const std::string& a) { return a.rfind("--store", 0) == 0; });
  if (!names_store) {
    server->store_path_ = TempPath("store");
    argv.push_back("--store=" + server->store_path_);
  }
  server->pid_ = Spawn(argv, out[1], err_fd);
  close(out[1]);
  close(err_fd);

  // The first stdout line is "listening on 127.0.0.1:PORT".
  std::string line;
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (line.find('\n') == std::string::npos && std::chrono::steady_clock::now() < end) {
    pollfd p{out[0], POLLIN, 0};
    if (poll(&p, 1, 100) <= 0) continue;
    char buffer[256];
    const ssize_t n = read(out[0], buffer, sizeof buffer);
    if (n <= 0) break;
    line.append(buffer, static_cast<size_t>(n));
  }
  close(out[0]);
  const std::string prefix = "listening on ";
  if (line.rfind(prefix, 0) != 0 || line.find('\n') == std::string::npos) {
    *error = "aperture-server did not start: " + line + "\n" + server->Log();
    return nullptr;  // the destructor kills it
  }
  server->address_ = line.substr(prefix.size(), line.find('\n') - prefix.size());
  return server;
}

ServerProcess::~ServerProcess() {
  if (pid_ > 0 && !reaped_) {
    kill(pid_, SIGKILL);
    WaitPid(pid_, 10);
  }
  if (!log_path_.empty()) unlink(log_path_.c_str());
  if (!store_path_.empty()) {
    std::error_code error;
    std::filesystem::remove_all(store_path_, error);
  }
}

void ServerProcess::Signal(int signal) const { kill(pid_, signal); }

std::optional<int> ServerProcess::WaitForExit(double seconds) {
  auto status = WaitPid(pid_, seconds);
  if (status) reaped_ = true;
  return status;
}

std::string ServerProcess::Log() const { return ReadAll(log_path_); }

namespace {

// A field of /proc/PID/status in kB ("VmRSS:", "VmHWM:"), as MiB; -1 if unreadable.
double StatusMb(pid_t pid, const std::string& field) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string key;
  while (status >> key) {
    if (key == field) {
      double kb = 0;
      status >> kb;
      return kb / 1024;
    }
    status.ignore(1 << 12, '\n');
  }
  return -1;
}

}  // namespace

double ServerProcess::ResidentMb() const { return StatusMb(pid_, "VmRSS:"); }
double ServerProcess::PeakResidentMb() const { return StatusMb(pid_, "VmHWM:"); }

CommandResult RunCommand(const std::vector<std::string>& argv, double timeout_seconds) {
  const std::string out_path = TempPath("out"), err_path = TempPath("err");
  const int out_fd = open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  const int err_fd = open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  const pid_t pid = Spawn(argv, out_fd, err_fd);
  close(out_fd);
  close(err_fd);
  CommandResult result;
  if (auto status = WaitPid(pid, timeout_seconds)) {
    result.exit_code = *status;
  } else {
    kill(pid, SIGKILL);
    WaitPid(pid, 10);
  }
  result.out = ReadAll(out_path);
  result.err = ReadAll(err_path);
  unlink(out_path.c_str());
  unlink(err_path.c_str());
  return result;
}

}  // namespace aperture::testing
