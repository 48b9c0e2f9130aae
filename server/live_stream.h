// RenderStream as a live image-generator channel: the newest state wins and frames are
// pipelined. Three threads serve one stream:
//   reader   reads requests and checks each (scene id, update); each gets an answer record in
//            arrival order and, if it passed, becomes the one waiting request, superseding
//            (answering as skipped) the request still waiting; a request that failed the check
//            is answered with its error at once;
//   renderer (the handler's thread) renders the waiting request once the pipeline has room;
//   writer   encodes rendered frames and writes every answer in arrival order.
// So while frame N is encoded and sent, frame N+1 renders; at most two rendered frames wait for
// the writer, and whatever the offered rate the latency stays within about two frame times.
// A skipped request's scene update is not lost: it is merged into the next request rendered.
//
// Flow control: the stream holds at most two requests whole (the one rendering and the newest
// waiting); a superseded request's body is dropped as it is superseded, leaving only its answer
// record (frame index, outcome, timings). At most kMaxUnwrittenAnswers answers wait for the
// writer: past that the reader stops reading until the writer has sent some, so a client that
// does not read its answers is held back by HTTP/2 flow control (its writes block) instead of
// making the server buffer its requests.
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
#include <string>

#include "absl/status/statusor.h"
#include "aperture/v1/render_service.grpc.pb.h"
#include "scene/scene.h"
#include "scene/scene_update.h"

namespace aperture {

using LiveClock = std::chrono::steady_clock;

// Whether a request can be rendered at all (its scene is loaded, its update would apply), checked
// until `stop` says stop: the stored scene it names, which the stream holds with the request (so
// the scene store keeps it) until the request is rendered.
using CheckFrameFn = std::function<absl::StatusOr<std::shared_ptr<const Scene>>(
    const v1::RenderFrameRequest& request, const std::function<bool()>& stop)>;
// Finishes a rendered frame: encodes it into the response.
using EncodeFrameFn = std::function<absl::Status(v1::RenderFrameResponse*)>;
// Renders one request of `scene` (the one its check gave: validation, its update, admission, the
// arena) and fills the response's timings; stops when `stop_at` passes. Returns what encodes the
// frame.
using RenderFrameFn = std::function<absl::StatusOr<EncodeFrameFn>(
    const v1::RenderFrameRequest& request, std::shared_ptr<const Scene> scene,
    LiveClock::time_point stop_at, v1::RenderFrameResponse* response)>;

// What the log line of an answer says of its request, kept in place of the request.
struct LiveRequestSummary {
  std::string scene_id;  // its first 64 characters (a scene id's length)
  uint32_t width = 0, height = 0;
  v1::RenderMode mode = v1::RENDER_MODE_RASTER;
};

// One request's answer, from the request's arrival until the answer is written: never the
// request's body.
struct LiveAnswer {
  uint64_t frame_index = 0;
  LiveClock::time_point received;
  // The server's wall clock at the request's arrival, and the host's send time it carried, both
  // nanoseconds since the Unix epoch: echoed in the answer for the host's transport delay.
  uint64_t received_unix_ns = 0, host_sent_unix_ns = 0;
  LiveClock::time_point rendered;  // kRendered since (the frame's hold before its encoding)
  LiveRequestSummary summary;
  enum class State { kWaiting, kRendering, kRendered, kAnswered } state = State::kWaiting;
  bool in_pipeline = false;  // rendering started: it holds a place until written
  EncodeFrameFn encode;      // kRendered
  absl::Status status;       // of the check, the render or the encode
  v1::RenderFrameResponse response;
};

struct LiveStreamCounts {
  uint64_t frames = 0, rendered = 0, skipped = 0, failed = 0;
};

class LiveStream {
 public:
  // Answers read but not yet written past which the stream stops reading (flow control).
  static constexpr size_t kMaxUnwrittenAnswers = 64;

  using Stream = grpc::ServerReaderWriter<v1::RenderFrameResponse, v1::RenderFrameRequest>;
  // `answered` is called once per request, after its answer is written (logs, counters).
  LiveStream(grpc::ServerContext* context, Stream* stream, CheckFrameFn check, RenderFrameFn render,
             std::function<void(const LiveAnswer&)> answered);

  // Serves the stream until the client is done or gone.
  LiveStreamCounts Run();

 private:
  // A request held whole: the one waiting to be rendered, then the one rendering.
  struct HeldRequest {
    v1::RenderFrameRequest request;
    std::shared_ptr<const Scene> scene;  // its check's, held against eviction
    std::shared_ptr<LiveAnswer> answer;
  };

  void ReadRequests();
  void RenderNewest();
  void WriteAnswers();
  // Whether the reader may read another request (the writer keeps up, or it has failed).
  bool RoomToRead() const;
  // The waiting request, which will not be rendered: answered now (the writer sends it in its
  // turn), its update carried to the next request rendered, its body dropped.
  void Skip(std::unique_ptr<HeldRequest> held, v1::FrameOutcome outcome, uint64_t superseded_by);

  grpc::ServerContext* const context_;
  Stream* const stream_;
  const CheckFrameFn check_;
  const RenderFrameFn render_;
  const std::function<void(const LiveAnswer&)> answered_;

  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<std::shared_ptr<LiveAnswer>> answers_;  // every request not yet answered, in order
  std::unique_ptr<HeldRequest> waiting_;             // the newest request not yet started
  // The scene updates of skipped requests, in order, for the next request that renders.
  MergedSceneUpdate carried_;
  int rendered_unwritten_ = 0;  // rendering or rendered frames the writer has not sent yet
  bool reading_done_ = false, rendering_done_ = false, writing_failed_ = false;
  LiveStreamCounts counts_;
};

}  // namespace aperture
