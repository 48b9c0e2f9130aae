#include <chrono>
#include <cstdio>
#include <fstream>
#include <mutex>
#include <thread>
#include <vector>

#include "absl/flags/flag.h"
#include "absl/strings/str_cat.h"
#include "channel.h"
#include "client_flags.h"
#include "commands.h"
#include "latency_stats.h"
#include "request_flags.h"
#include "scene_upload.h"

namespace aperture {
namespace {

// Cameras from a CSV file (X,Y,Z,YAW,PITCH,ROLL per line; '#' lines skipped), or the base camera
// flying forward at 60 m/s along -z.
absl::StatusOr<std::vector<v1::Camera>> CameraPath(const v1::Camera& base, int frames,
                                                   double rate) {
  std::vector<v1::Camera> path;
  if (const std::string file = absl::GetFlag(FLAGS_path); !file.empty()) {
    std::ifstream in(file);
    if (!in) return absl::NotFoundError(absl::StrCat("cannot read --path ", file));
    std::string line;
    while (std::getline(in, line) && static_cast<int>(path.size()) < frames) {
      if (line.empty() || line[0] == '#') continue;
      v1::Camera camera = base;
      if (auto s = ParseCameraInto(line, &camera); !s.ok()) return s;
      path.push_back(camera);
    }
    return path;
  }
  for (int i = 0; i < frames; ++i) {
    v1::Camera camera = base;
    camera.mutable_position()->set_z(base.position().z() - 60.0 * i / rate);
    path.push_back(camera);
  }
  return path;
}

}  // namespace

int RunSim() {
  using Clock = std::chrono::steady_clock;
  auto fail = [](const absl::Status& status) {
    std::fprintf(stderr, "aperture sim: error: %s\n", std::string(status.message()).c_str());
    return absl::IsInvalidArgument(status) ? 2 : 1;
  };
  const double rate = absl::GetFlag(FLAGS_rate);
  if (!(rate > 0)) return fail(absl::InvalidArgumentError("--rate must be > 0"));
  auto stub = v1::Render::NewStub(MakeChannel(absl::GetFlag(FLAGS_server)));
  auto scene = LoadSceneOnServer(*stub, absl::GetFlag(FLAGS_scene));
  if (!scene.ok()) return fail(scene.status());
  auto base = FrameRequestFromFlags(*scene);
  if (!base.ok()) return fail(base.status());
  auto path = CameraPath(base->camera(), absl::GetFlag(FLAGS_frames), rate);
  if (!path.ok()) return fail(path.status());
  const size_t frames = path->size();

  grpc::ClientContext context;
  auto stream = stub->RenderStream(&context);
  const auto slot =
      std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / rate));
  const auto start = Clock::now() + std::chrono::milliseconds(20);
  std::vector<Clock::time_point> sent(frames);
  std::mutex mutex;
  std::thread writer([&] {
    for (size_t i = 0; i < frames; ++i) {
      std::this_thread::sleep_until(start + slot * static_cast<int64_t>(i));
      v1::RenderFrameRequest request = *base;
      *request.mutable_camera() = (*path)[i];
      request.set_frame_index(i);
      {
        std::lock_guard lock(mutex);
        sent[i] = Clock::now();
      }
      if (!stream->Write(request)) break;
    }
    stream->WritesDone();
  });

  std::vector<double> latencies;
  size_t received = 0, dropped = 0, late = 0, skipped = 0;
  Clock::time_point last_frame = start;
  v1::RenderFrameResponse response;
  while (stream->Read(&response)) {
    const auto now = Clock::now();
    const size_t i = response.frame_index();
    ++received;
    if (response.status_code() != 0 || i >= frames) {
      ++dropped;
      continue;
    }
    // The server rendered a newer state instead (newest state wins): not an error.
    if (response.outcome() != v1::FRAME_OUTCOME_RENDERED) {
      ++skipped;
      continue;
    }
    Clock::time_point sent_at;
    {
      std::lock_guard lock(mutex);
      sent_at = sent[i];
    }
    latencies.push_back(std::chrono::duration<double, std::milli>(now - sent_at).count());
    last_frame = now;
    // A frame is late when it arrives after the end of its own slot.
    if (now > start + slot * static_cast<int64_t>(i + 1)) ++late;
  }
  writer.join();
  const grpc::Status status = stream->Finish();
  dropped += frames - received;
  const LatencySummary s = Summarize(latencies);
  // Frames shown per second of the run, from the first slot to the last frame received.
  const double seconds = std::chrono::duration<double>(last_frame - start).count();
  const double achieved = seconds > 0 ? static_cast<double>(s.count) / seconds : 0.0;
  if (absl::GetFlag(FLAGS_json)) {
    std::printf(
        "{\"frames\": %zu, \"rate_hz\": %.3f, \"achieved_hz\": %.3f, \"ok\": %zu, "
        "\"late\": %zu, \"skipped\": %zu, \"dropped\": %zu, \"latency_ms\": {\"p50\": %.3f, "
        "\"p90\": %.3f, \"p99\": %.3f, \"max\": %.3f}, \"status\": \"%s\"}\n",
        frames, rate, achieved, s.count, late, skipped, dropped, s.p50, s.p90, s.p99, s.max,
        status.ok() ? "OK" : status.error_message().c_str());
  } else {
    std::printf(
        "%zu frames offered at %.2f Hz: %zu rendered (%.2f Hz achieved), %zu late for their "
        "slot, %zu skipped for a newer state, %zu dropped\n",
        frames, rate, s.count, achieved, late, skipped, dropped);
    std::printf("latency ms: p50 %.2f  p90 %.2f  p99 %.2f  max %.2f\n", s.p50, s.p90, s.p99, s.max);
    if (!status.ok()) std::printf("stream ended: %s\n", status.error_message().c_str());
  }
  return status.ok() && dropped == 0 ? 0 : 1;
}

}  // namespace aperture
