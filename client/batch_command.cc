#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <thread>
#include <vector>

#include "absl/flags/flag.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_split.h"
#include "batch_job.h"
#include "channel.h"
#include "client_flags.h"
#include "commands.h"
#include "request_flags.h"
#include "scene_upload.h"

// After the protobuf headers: OpenImageIO's byte-swap macros break protobuf's port.h.
#include <OpenImageIO/imageio.h>

namespace aperture {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// A frame already written is kept when it opens as an EXR of the requested size.
bool IsValidFrame(const std::string& path, uint32_t width, uint32_t height) {
  std::error_code error;
  if (!fs::is_regular_file(path, error)) return false;
  auto input = OIIO::ImageInput::open(path);
  if (!input) return false;
  const OIIO::ImageSpec& spec = input->spec();
  return spec.width == static_cast<int>(width) && spec.height == static_cast<int>(height);
}

// Written under a temporary name and renamed: an interrupted write never looks like a frame.
bool WriteFrame(const std::string& path, const std::string& bytes) {
  const std::string temporary = path + ".part";
  {
    std::ofstream out(temporary, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out.flush()) return false;
  }
  std::error_code error;
  fs::rename(temporary, path, error);
  return !error;
}

}  // namespace

int RunBatch(const std::string& job_path) {
  auto fail = [](const absl::Status& status) {
    std::fprintf(stderr, "aperture batch: error: %s\n", std::string(status.message()).c_str());
    return absl::IsInvalidArgument(status) ? 2 : 1;
  };
  auto job = ReadBatchJob(job_path);
  if (!job.ok()) return fail(job.status());
  absl::SetFlag(&FLAGS_scene, job->scene);
  if (!job->size.empty()) absl::SetFlag(&FLAGS_size, job->size);
  if (!job->filter.empty()) absl::SetFlag(&FLAGS_filter, job->filter);
  const std::string out_dir = absl::GetFlag(FLAGS_o);
  std::error_code error;
  fs::create_directories(out_dir, error);
  if (error) return fail(absl::InternalError(absl::StrCat("cannot create ", out_dir)));

  // Every server gets the scene (its textures uploaded when missing); the id is the same on all.
  std::vector<std::string> servers =
      absl::StrSplit(absl::GetFlag(FLAGS_servers), ',', absl::SkipEmpty());
  std::vector<std::string> ready;
  SceneOnServer loaded;
  for (const std::string& server : servers) {
    auto stub = v1::Render::NewStub(MakeChannel(server));
    auto scene = LoadSceneOnServer(*stub, job->scene);
    if (!scene.ok()) {
      std::fprintf(stderr, "aperture batch: %s: %s; not used\n", server.c_str(),
                   std::string(scene.status().message()).c_str());
      continue;
    }
    loaded = *std::move(scene);
    ready.push_back(server);
  }
  if (ready.empty()) return fail(absl::UnavailableError("no server could load the scene"));
  auto base = FrameRequestFromFlags(loaded);
  if (!base.ok()) return fail(base.status());

  // gRPC's round_robin policy spreads the frames over the servers; a failed frame is retried,
  // and the policy sends the retry to the next server.
  grpc::ChannelArguments args;
  args.SetMaxReceiveMessageSize(-1);
  args.SetLoadBalancingPolicyName("round_robin");
  auto stub = v1::Render::NewStub(grpc::CreateCustomChannel(
      absl::StrCat("ipv4:", absl::StrJoin(ready, ",")), ClientCredentials(), args));

  const size_t frames = job->cameras.size();
  const uint32_t width = base->options().width(), height = base->options().height();
  const int attempts = 3 * static_cast<int>(ready.size());
  std::atomic<size_t> next{0}, rendered{0}, skipped{0}, failed{0}, retries{0};
  std::mutex print;
  const auto start = Clock::now();
  auto progress = [&] {
    const size_t done = rendered + skipped + failed;
    const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    const double eta = rendered > 0 ? elapsed / rendered * (frames - done) : 0;
    const int bar = static_cast<int>(30 * done / frames);
    std::lock_guard lock(print);
    std::fprintf(stderr, "\r[%s%s] %zu/%zu frames, ETA %.0f s ", std::string(bar, '#').c_str(),
                 std::string(30 - bar, ' ').c_str(), done, frames, eta);
  };

  std::vector<std::thread> workers;
  for (int w = 0; w < std::max(1, absl::GetFlag(FLAGS_concurrency)); ++w) {
    workers.emplace_back([&] {
      for (size_t i = next++; i < frames; i = next++) {
        const std::string path =
            (fs::path(out_dir) / absl::StrFormat("frame_%06d.exr", i)).string();
        if (IsValidFrame(path, width, height)) {
          ++skipped;
          progress();
          continue;
        }
        v1::RenderFrameRequest request = *base;
        request.set_frame_index(i);
        bool ok = ParseCameraInto(job->cameras[i], request.mutable_camera()).ok();
        for (int attempt = 0; ok && attempt < attempts; ++attempt) {
          if (attempt > 0) {
            ++retries;
            std::this_thread::sleep_for(std::chrono::milliseconds(50));
          }
          grpc::ClientContext context;
          context.set_deadline(DeadlineIn(absl::GetFlag(FLAGS_deadline_s)));
          v1::RenderFrameResponse response;
          if (stub->RenderFrame(&context, request, &response).ok() &&
              WriteFrame(path, response.exr())) {
            ++rendered;
            progress();
            break;
          }
          if (attempt + 1 == attempts) ok = false;
        }
        if (!ok) {
          ++failed;
          progress();
        }
      }
    });
  }
  for (std::thread& t : workers) t.join();
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  std::fprintf(stderr, "\n");
  std::printf(
      "batch: %zu frames on %zu servers: %zu rendered, %zu skipped (already valid), "
      "%zu failed, %zu retries in %.2f s\n",
      frames, ready.size(), rendered.load(), skipped.load(), failed.load(), retries.load(),
      seconds);
  return failed == 0 ? 0 : 1;
}

}  // namespace aperture
