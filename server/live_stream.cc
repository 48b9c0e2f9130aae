#include "live_stream.h"

#include <thread>
#include <utility>

#include "scene/scene_update.h"
#include "status_mapping.h"
#include "stop_check.h"

namespace aperture {
namespace {

// A render starts only while at most this many rendered frames wait for the writer: one being
// encoded and sent while the next renders, never a backlog of finished frames.
constexpr int kRenderedAhead = 1;

// How often a reader held back by flow control looks whether the client has gone.
constexpr std::chrono::milliseconds kCancelPoll{50};

// A scene id is 64 hex digits: what the log needs of a longer one.
constexpr size_t kSummaryIdChars = 64;

double MillisecondsSince(LiveClock::time_point start) {
  return std::chrono::duration<double, std::milli>(LiveClock::now() - start).count();
}

uint64_t UnixNanosecondsNow() {
  return static_cast<uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                   std::chrono::system_clock::now().time_since_epoch())
                                   .count());
}

LiveClock::time_point FrameDeadline(const LiveAnswer& answer, uint32_t deadline_ms) {
  return deadline_ms > 0 ? answer.received + std::chrono::milliseconds(deadline_ms)
                         : LiveClock::time_point::max();
}

}  // namespace

LiveStream::LiveStream(grpc::ServerContext* context, Stream* stream, CheckFrameFn check,
                       RenderFrameFn render, std::function<void(const LiveAnswer&)> answered)
    : context_(context),
      stream_(stream),
      check_(std::move(check)),
      render_(std::move(render)),
      answered_(std::move(answered)) {}

LiveStreamCounts LiveStream::Run() {
  std::thread reader([this] { ReadRequests(); });
  std::thread writer([this] { WriteAnswers(); });
  RenderNewest();
  writer.join();
  // A writer that failed has cancelled the call, which ends the reader's Read too.
  reader.join();
  return counts_;
}

bool LiveStream::RoomToRead() const {
  return writing_failed_ || answers_.size() < kMaxUnwrittenAnswers;
}

void LiveStream::Skip(std::unique_ptr<HeldRequest> held, v1::FrameOutcome outcome,
                      uint64_t superseded_by) {
  LiveAnswer& answer = *held->answer;
  answer.state = LiveAnswer::State::kAnswered;
  answer.response.set_frame_index(answer.frame_index);
  answer.response.set_outcome(outcome);
  answer.response.set_superseded_by(superseded_by);
  answer.response.mutable_timings()->set_total_ms(MillisecondsSince(answer.received));
  // Its update holds from its frame on: the next request rendered applies it first.
  if (held->request.has_update()) carried_.Merge(held->request.update());
}

void LiveStream::ReadRequests() {
  for (;;) {
    {
      // Flow control: while the writer is behind, nothing is read, so the client's requests wait
      // in its own buffers. A reader held here is not in Read, so it looks for the client's
      // cancellation itself.
      std::unique_lock lock(mutex_);
      while (!RoomToRead() && !context_->IsCancelled()) changed_.wait_for(lock, kCancelPoll);
      if (writing_failed_ || context_->IsCancelled()) break;
    }
    auto held = std::make_unique<HeldRequest>();
    if (!stream_->Read(&held->request)) break;
    auto answer = std::make_shared<LiveAnswer>();
    answer->received = LiveClock::now();
    answer->received_unix_ns = UnixNanosecondsNow();
    answer->host_sent_unix_ns = held->request.host_sent_unix_ns();
    answer->frame_index = held->request.frame_index();
    answer->summary.scene_id = held->request.scene_id().substr(0, kSummaryIdChars);
    answer->summary.width = held->request.options().width();
    answer->summary.height = held->request.options().height();
    answer->summary.mode = held->request.options().mode();
    StopCheck stop(context_, FrameDeadline(*answer, held->request.deadline_ms()));
    auto checked = check_(held->request, [&] { return stop(); });
    {
      std::lock_guard lock(mutex_);
      answers_.push_back(answer);
      if (!checked.ok()) {  // never rendered, supersedes nothing: answered in its turn
        answer->status = WhyStopped(checked.status(), stop, "while its scene update was checked");
        answer->state = LiveAnswer::State::kAnswered;
      } else {
        held->scene = *std::move(checked);
        held->answer = answer;
        if (waiting_)
          Skip(std::move(waiting_), v1::FRAME_OUTCOME_SKIPPED_SUPERSEDED, answer->frame_index);
        waiting_ = std::move(held);
      }
    }
    changed_.notify_all();
  }
  {
    std::lock_guard lock(mutex_);
    reading_done_ = true;
  }
  changed_.notify_all();
}

void LiveStream::RenderNewest() {
  for (;;) {
    std::unique_ptr<HeldRequest> held;
    {
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [&] {
        return writing_failed_ || (waiting_ && rendered_unwritten_ <= kRenderedAhead) ||
               (reading_done_ && !waiting_);
      });
      if (writing_failed_ || !waiting_) break;
      held = std::move(waiting_);
      if (LiveClock::now() > FrameDeadline(*held->answer, held->request.deadline_ms())) {
        Skip(std::move(held), v1::FRAME_OUTCOME_SKIPPED_LATE, 0);
        changed_.notify_all();
        continue;
      }
      if (!carried_.empty()) {  // the skipped requests' updates first, then its own
        carried_.Merge(held->request.update());
        *held->request.mutable_update() = carried_.Take();
      }
      held->answer->state = LiveAnswer::State::kRendering;
      held->answer->in_pipeline = true;
      ++rendered_unwritten_;
    }
    LiveAnswer& answer = *held->answer;
    answer.response.mutable_timings()->set_wait_ms(MillisecondsSince(answer.received));
    auto encode = render_(held->request, held->scene,
                          FrameDeadline(answer, held->request.deadline_ms()), &answer.response);
    {
      std::lock_guard lock(mutex_);
      if (encode.ok()) {
        answer.encode = std::move(*encode);
        answer.state = LiveAnswer::State::kRendered;
        answer.rendered = LiveClock::now();
      } else {
        answer.status = encode.status();
        answer.state = LiveAnswer::State::kAnswered;
      }
    }
    changed_.notify_all();
    held.reset();  // the request's body; its scene stays held by the renderer's LiveScene
  }
  {
    std::lock_guard lock(mutex_);
    rendering_done_ = true;
  }
  changed_.notify_all();
}

void LiveStream::WriteAnswers() {
  for (;;) {
    std::shared_ptr<LiveAnswer> answer;
    {
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [&] {
        if (answers_.empty()) return rendering_done_;
        const LiveAnswer::State state = answers_.front()->state;
        return state == LiveAnswer::State::kRendered || state == LiveAnswer::State::kAnswered;
      });
      if (answers_.empty()) break;
      answer = answers_.front();
    }
    if (answer->state == LiveAnswer::State::kRendered) {
      v1::FrameTimings& timings = *answer->response.mutable_timings();
      timings.set_hold_ms(MillisecondsSince(answer->rendered));
      answer->status = answer->encode(&answer->response);
      answer->encode = nullptr;  // the rendered image goes with it
      // The whole stay in the server: from the request's arrival, its wait and hold included.
      timings.set_total_ms(MillisecondsSince(answer->received));
    }
    v1::RenderFrameResponse& response = answer->response;
    response.set_frame_index(answer->frame_index);
    if (!answer->status.ok()) {
      response.Clear();
      response.set_frame_index(answer->frame_index);
      response.set_status_code(static_cast<int>(answer->status.code()));
      response.set_status_message(StatusMessageForClient(answer->status.message()));
    }
    response.set_host_sent_unix_ns(answer->host_sent_unix_ns);
    response.set_server_received_unix_ns(answer->received_unix_ns);
    response.set_server_sent_unix_ns(UnixNanosecondsNow());
    const bool written = !context_->IsCancelled() && stream_->Write(response);
    ++counts_.frames;
    if (response.outcome() != v1::FRAME_OUTCOME_RENDERED)
      ++counts_.skipped;
    else if (answer->status.ok())
      ++counts_.rendered;
    else
      ++counts_.failed;
    answered_(*answer);
    {
      std::lock_guard lock(mutex_);
      answers_.pop_front();
      if (answer->in_pipeline) --rendered_unwritten_;
      if (!written) writing_failed_ = true;
    }
    changed_.notify_all();
    if (!written) {
      context_->TryCancel();  // ends the reader's Read
      break;
    }
  }
}

}  // namespace aperture
