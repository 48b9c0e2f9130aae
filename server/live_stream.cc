#include "live_stream.h"

#include <thread>
#include <utility>

#include "scene/scene_update.h"
#include "status_mapping.h"

namespace aperture {
namespace {

// A render starts only while at most this many rendered frames wait for the writer: one being
// encoded and sent while the next renders, never a backlog of finished frames.
constexpr int kRenderedAhead = 1;

double MillisecondsSince(LiveClock::time_point start) {
  return std::chrono::duration<double, std::milli>(LiveClock::now() - start).count();
}

}  // namespace

LiveStream::LiveStream(grpc::ServerContext* context, Stream* stream, CheckFrameFn check,
                       RenderFrameFn render, std::function<void(const LiveFrame&)> answered)
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

void LiveStream::Skip(LiveFrame& frame, v1::FrameOutcome outcome, uint64_t superseded_by) {
  frame.state = LiveFrame::State::kAnswered;
  frame.response.set_frame_index(frame.request.frame_index());
  frame.response.set_outcome(outcome);
  frame.response.set_superseded_by(superseded_by);
  frame.response.mutable_timings()->set_total_ms(MillisecondsSince(frame.received));
  // Its update holds from its frame on: the next request rendered applies it first.
  if (frame.request.has_update()) {
    if (!carried_) carried_.emplace();
    MergeSceneUpdate(frame.request.update(), &*carried_);
  }
}

void LiveStream::ReadRequests() {
  auto frame = std::make_shared<LiveFrame>();
  while (stream_->Read(&frame->request)) {
    frame->received = LiveClock::now();
    absl::Status checked = check_(frame->request);
    {
      std::lock_guard lock(mutex_);
      if (!checked.ok()) {  // never rendered, supersedes nothing: answered in its turn
        frame->status = std::move(checked);
        frame->state = LiveFrame::State::kAnswered;
        answers_.push_back(frame);
        changed_.notify_all();
        frame = std::make_shared<LiveFrame>();
        continue;
      }
      if (waiting_)
        Skip(*waiting_, v1::FRAME_OUTCOME_SKIPPED_SUPERSEDED, frame->request.frame_index());
      answers_.push_back(frame);
      waiting_ = frame;
    }
    changed_.notify_all();
    frame = std::make_shared<LiveFrame>();
  }
  {
    std::lock_guard lock(mutex_);
    reading_done_ = true;
  }
  changed_.notify_all();
}

void LiveStream::RenderNewest() {
  for (;;) {
    std::shared_ptr<LiveFrame> frame;
    {
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [&] {
        return writing_failed_ || (waiting_ && rendered_unwritten_ <= kRenderedAhead) ||
               (reading_done_ && !waiting_);
      });
      if (writing_failed_ || !waiting_) break;
      frame = std::exchange(waiting_, nullptr);
      const uint32_t deadline_ms = frame->request.deadline_ms();
      if (deadline_ms > 0 &&
          LiveClock::now() > frame->received + std::chrono::milliseconds(deadline_ms)) {
        Skip(*frame, v1::FRAME_OUTCOME_SKIPPED_LATE, 0);
        changed_.notify_all();
        continue;
      }
      if (carried_) {  // the skipped requests' updates first, then its own
        MergeSceneUpdate(frame->request.update(), &*carried_);
        *frame->request.mutable_update() = *std::move(carried_);
        carried_.reset();
      }
      frame->state = LiveFrame::State::kRendering;
      ++rendered_unwritten_;
    }
    const uint32_t deadline_ms = frame->request.deadline_ms();
    const LiveClock::time_point stop_at =
        deadline_ms > 0 ? frame->received + std::chrono::milliseconds(deadline_ms)
                        : LiveClock::time_point::max();
    auto encode = render_(frame->request, stop_at, &frame->response);
    {
      std::lock_guard lock(mutex_);
      if (encode.ok()) {
        frame->encode = std::move(*encode);
        frame->state = LiveFrame::State::kRendered;
      } else {
        frame->status = encode.status();
        frame->state = LiveFrame::State::kAnswered;
      }
    }
    changed_.notify_all();
  }
  {
    std::lock_guard lock(mutex_);
    rendering_done_ = true;
  }
  changed_.notify_all();
}

void LiveStream::WriteAnswers() {
  for (;;) {
    std::shared_ptr<LiveFrame> frame;
    {
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [&] {
        if (answers_.empty()) return rendering_done_;
        const LiveFrame::State state = answers_.front()->state;
        return state == LiveFrame::State::kRendered || state == LiveFrame::State::kAnswered;
      });
      if (answers_.empty()) break;
      frame = answers_.front();
    }
    // Not skipped: it held a place in the pipeline (rendered, or failed while rendering).
    const bool rendered = frame->response.outcome() == v1::FRAME_OUTCOME_RENDERED;
    if (frame->state == LiveFrame::State::kRendered) {
      frame->status = frame->encode(&frame->response);
      frame->encode = nullptr;  // the rendered image goes with it
    }
    v1::RenderFrameResponse& response = frame->response;
    response.set_frame_index(frame->request.frame_index());
    if (!frame->status.ok()) {
      response.Clear();
      response.set_frame_index(frame->request.frame_index());
      response.set_status_code(static_cast<int>(frame->status.code()));
      response.set_status_message(StatusMessageForClient(frame->status.message()));
    }
    const bool written = !context_->IsCancelled() && stream_->Write(response);
    ++counts_.frames;
    if (response.outcome() != v1::FRAME_OUTCOME_RENDERED)
      ++counts_.skipped;
    else if (frame->status.ok())
      ++counts_.rendered;
    else
      ++counts_.failed;
    answered_(*frame);
    {
      std::lock_guard lock(mutex_);
      answers_.pop_front();
      if (rendered) --rendered_unwritten_;
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
