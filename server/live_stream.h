// RenderStream as a live image-generator channel (issue 20): the newest state wins and frames are
// pipelined. Three threads serve one stream:
//   reader   reads requests and checks each (scene id, update); each joins the answer queue in
//            arrival order and, if it passed, becomes the one waiting request, superseding
//            (answering as skipped) any request still waiting; a request that failed the check
//            is answered with its error at once;
//   renderer (the handler's thread) renders the waiting request once the pipeline has room;
//   writer   encodes rendered frames and writes every answer in arrival order.
// So while frame N is encoded and sent, frame N+1 renders; at most two rendered frames wait for
// the writer, and whatever the offered rate the latency stays within about two frame times.
// A skipped request's scene update is not lost: it is merged into the next request rendered.
#pragma once

#include <grpcpp/server_context.h>
#include <grpcpp/support/sync_stream.h>

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>

#include "absl/status/statusor.h"
#include "aperture/v1/render_service.grpc.pb.h"

namespace aperture {

using LiveClock = std::chrono::steady_clock;

// Whether a request can be rendered at all (its scene is loaded, its update would apply).
using CheckFrameFn = std::function<absl::Status(const v1::RenderFrameRequest& request)>;
// Finishes a rendered frame: encodes it into the response.
using EncodeFrameFn = std::function<absl::Status(v1::RenderFrameResponse*)>;
// Renders one request (validation, admission, the arena) and fills the response's timings; stops
// when `stop_at` passes. Returns what encodes the frame.
using RenderFrameFn = std::function<absl::StatusOr<EncodeFrameFn>(
    const v1::RenderFrameRequest& request, LiveClock::time_point stop_at,
    v1::RenderFrameResponse* response)>;

// One request of the stream from arrival to answer.
struct LiveFrame {
  v1::RenderFrameRequest request;
  LiveClock::time_point received;
  enum class State { kWaiting, kRendering, kRendered, kAnswered } state = State::kWaiting;
  EncodeFrameFn encode;  // kRendered
  absl::Status status;   // of the render or the encode
  v1::RenderFrameResponse response;
};

struct LiveStreamCounts {
  uint64_t frames = 0, rendered = 0, skipped = 0, failed = 0;
};

class LiveStream {
 public:
  using Stream = grpc::ServerReaderWriter<v1::RenderFrameResponse, v1::RenderFrameRequest>;
  // `answered` is called once per request, after its answer is written (logs, counters).
  LiveStream(grpc::ServerContext* context, Stream* stream, CheckFrameFn check, RenderFrameFn render,
             std::function<void(const LiveFrame&)> answered);

  // Serves the stream until the client is done or gone.
  LiveStreamCounts Run();

 private:
  void ReadRequests();
  void RenderNewest();
  void WriteAnswers();
  // A request that will not be rendered: answered now (the writer sends it in its turn).
  void Skip(LiveFrame& frame, v1::FrameOutcome outcome, uint64_t superseded_by);

  grpc::ServerContext* const context_;
  Stream* const stream_;
  const CheckFrameFn check_;
  const RenderFrameFn render_;
  const std::function<void(const LiveFrame&)> answered_;

  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<std::shared_ptr<LiveFrame>> answers_;  // every request not yet answered, in order
  std::shared_ptr<LiveFrame> waiting_;              // the newest request not yet started
  // The scene updates of skipped requests, in order, for the next request that renders.
  std::optional<v1::SceneUpdate> carried_;
  int rendered_unwritten_ = 0;  // rendering or rendered frames the writer has not sent yet
  bool reading_done_ = false, rendering_done_ = false, writing_failed_ = false;
  LiveStreamCounts counts_;
};

}  // namespace aperture
