// Cancels calls that went quiet: a client that opens an upload stream and
// stops sending would otherwise hold its buffer and a gRPC thread until its deadline, which may
// be never. A watched call touches its watch whenever a message arrives; one thread looks at the
// watches a few times per idle period and cancels (ServerContext::TryCancel) a call idle longer
// than the limit, which ends its blocked Read.
#pragma once

#include <grpcpp/server_context.h>

#include <chrono>
#include <condition_variable>
#include <list>
#include <memory>
#include <mutex>
#include <thread>

namespace aperture {

class IdleWatchdog {
  struct Entry {
    grpc::ServerContext* context;
    std::chrono::steady_clock::time_point last;
    bool expired = false;
  };

 public:
  explicit IdleWatchdog(std::chrono::milliseconds idle_limit);
  ~IdleWatchdog();

  class Watch {
   public:
    ~Watch();
    void Touch();          // a message arrived
    bool Expired() const;  // the watchdog cancelled the call for idleness
   private:
    friend class IdleWatchdog;
    Watch(IdleWatchdog* dog, std::list<Entry>::iterator entry) : dog_(dog), entry_(entry) {}
    IdleWatchdog* dog_;
    std::list<Entry>::iterator entry_;
  };

  std::unique_ptr<Watch> Start(grpc::ServerContext* context);
  std::chrono::milliseconds idle_limit() const { return idle_limit_; }

 private:
  void Run();

  const std::chrono::milliseconds idle_limit_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;
  std::list<Entry> entries_;
  std::thread thread_;
};

}  // namespace aperture
