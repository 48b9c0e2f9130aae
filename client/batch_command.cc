#include <arpa/inet.h>
#include <netdb.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
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
#include "batch_progress.h"
#include "channel.h"
#include "client_flags.h"
#include "commands.h"
#include "contact_sheet.h"
#include "exit_status.h"
#include "grpc_status.h"
#include "request_flags.h"
#include "scene_upload.h"

// After the protobuf headers: OpenImageIO's byte-swap macros break protobuf's port.h.
#include <OpenImageIO/imageio.h>

namespace aperture {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// A frame already written is kept (and passes --check) when it reads back completely as an
// OpenEXR image of the requested size: header and every pixel, so a file cut short on a shared
// file system (a node lost mid-write) is rendered again. Empty when valid, else why not.
std::string InvalidFrame(const std::string& path, uint32_t width, uint32_t height) {
  std::error_code error;
  if (!fs::exists(path, error)) return "missing";
  if (!fs::is_regular_file(path, error)) return "not a regular file";
  auto input = OIIO::ImageInput::open(path);
  if (!input) return "does not open as an image";
  if (std::string(input->format_name()) != "openexr") return "not an OpenEXR file";
  const OIIO::ImageSpec& spec = input->spec();
  if (spec.width != static_cast<int>(width) || spec.height != static_cast<int>(height))
    return absl::StrFormat("%dx%d, expected %ux%u", spec.width, spec.height, width, height);
  std::vector<float> pixels(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
  if (!input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data()))
    return "pixels do not read back (truncated or corrupt)";
  return "";
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

// Frames keep their job-wide number whatever the shard.
std::string FramePath(const std::string& out_dir, size_t frame) {
  return (fs::path(out_dir) / absl::StrFormat("frame_%06zu.exr", frame)).string();
}

// --servers entries as IPv4 addresses: an IPv4 literal is kept, a host name is resolved to all
// of its IPv4 addresses (a Kubernetes headless Service or a compose service name yields every
// server behind it), so the scene is loaded on each and round_robin spreads the frames over them.
std::vector<std::string> ResolveServers(const std::string& list) {
  std::vector<std::string> out;
  for (const std::string& entry :
       std::vector<std::string>(absl::StrSplit(list, ',', absl::SkipEmpty()))) {
    const size_t colon = entry.rfind(':');
    const std::string host = colon == std::string::npos ? entry : entry.substr(0, colon);
    const std::string port = colon == std::string::npos ? "50051" : entry.substr(colon + 1);
    in_addr literal{};
    if (inet_pton(AF_INET, host.c_str(), &literal) == 1) {
      out.push_back(absl::StrCat(host, ":", port));
      continue;
    }
    addrinfo hints{};
    hints.ai_family = AF_INET;
    hints.ai_socktype = SOCK_STREAM;
    addrinfo* found = nullptr;
    if (const int rc = getaddrinfo(host.c_str(), port.c_str(), &hints, &found); rc != 0) {
      std::fprintf(stderr, "aperture batch: %s: %s; not used\n", entry.c_str(), gai_strerror(rc));
      continue;
    }
    std::vector<std::string> addresses;
    for (addrinfo* a = found; a != nullptr; a = a->ai_next) {
      char text[INET_ADDRSTRLEN] = {};
      const auto* sin = reinterpret_cast<const sockaddr_in*>(a->ai_addr);
      if (inet_ntop(AF_INET, &sin->sin_addr, text, sizeof text) != nullptr)
        addresses.push_back(absl::StrCat(text, ":", port));
    }
    freeaddrinfo(found);
    std::sort(addresses.begin(), addresses.end());
    addresses.erase(std::unique(addresses.begin(), addresses.end()), addresses.end());
    out.insert(out.end(), addresses.begin(), addresses.end());
  }
  // The same server named twice (by name and address) is used once.
  std::vector<std::string> unique;
  for (const std::string& a : out)
    if (std::find(unique.begin(), unique.end(), a) == unique.end()) unique.push_back(a);
  return unique;
}

// The contact sheet of the frames on disk, next to them (one per shard when sharded); a sheet that
// cannot be written is a warning: the frames are what the job is for.
void WriteSheet(const std::vector<size_t>& owned, const std::string& out_dir, const Shard& shard) {
  std::vector<std::pair<size_t, std::string>> frames;
  std::error_code error;
  for (size_t f : owned)
    if (fs::exists(FramePath(out_dir, f), error)) frames.push_back({f, FramePath(out_dir, f)});
  if (frames.empty()) return;
  const std::string name = shard.count == 1 ? "contact_sheet.png"
                                            : absl::StrFormat("contact_sheet-shard-%zu-of-%zu.png",
                                                              shard.index, shard.count);
  const std::string path = (fs::path(out_dir) / name).string();
  if (auto s = WriteContactSheet(frames, path); !s.ok())
    std::fprintf(stderr, "aperture batch: warning: %s\n", std::string(s.message()).c_str());
  else
    std::printf("contact sheet: %s (%zu frames)\n", path.c_str(),
                std::min(frames.size(), kMaxThumbnails));
}

// --check: reads back the shard's frames, lists those missing or invalid; no server involved.
int CheckFrames(const std::string& out_dir, const std::vector<size_t>& frames,
                const std::string& what) {
  uint32_t width = 0, height = 0;
  if (auto s = ParseSize(absl::GetFlag(FLAGS_size), &width, &height); !s.ok()) {
    std::fprintf(stderr, "aperture batch: error: %s\n", std::string(s.message()).c_str());
    return 2;
  }
  std::vector<std::string> problems(frames.size());
  std::atomic<size_t> next{0};
  std::vector<std::thread> workers;
  for (int w = 0; w < std::max(1, absl::GetFlag(FLAGS_concurrency)); ++w) {
    workers.emplace_back([&] {
      for (size_t k = next++; k < frames.size(); k = next++)
        problems[k] = InvalidFrame(FramePath(out_dir, frames[k]), width, height);
    });
  }
  for (std::thread& t : workers) t.join();
  size_t missing = 0, invalid = 0;
  for (size_t k = 0; k < frames.size(); ++k) {
    if (problems[k].empty()) continue;
    (problems[k] == "missing" ? missing : invalid)++;
    std::printf("%s: %s\n", FramePath(out_dir, frames[k]).c_str(), problems[k].c_str());
  }
  std::printf("check: %s, %ux%u: %zu valid, %zu missing, %zu invalid\n", what.c_str(), width,
              height, frames.size() - missing - invalid, missing, invalid);
  return missing + invalid == 0 ? 0 : 1;
}

}  // namespace

int RunBatch(const std::string& job_path) {
  auto fail = [](const absl::Status& status) { return Fail("batch", status); };
  auto job = ReadBatchJob(job_path);
  if (!job.ok()) return fail(InputError(job.status()));
  auto shard = ParseShard(absl::GetFlag(FLAGS_shard));
  if (!shard.ok()) return fail(shard.status());
  absl::SetFlag(&FLAGS_scene, job->scene);
  if (!job->size.empty()) absl::SetFlag(&FLAGS_size, job->size);
  if (!job->filter.empty()) absl::SetFlag(&FLAGS_filter, job->filter);
  const std::string out_dir = absl::GetFlag(FLAGS_o);

  // This shard's frames, by their job-wide numbers.
  std::vector<size_t> owned;
  for (size_t f = 0; f < job->cameras.size(); ++f)
    if (shard->Owns(f)) owned.push_back(f);
  const std::string what = shard->count == 1
                               ? absl::StrFormat("%zu frames", owned.size())
                               : absl::StrFormat("shard %zu/%zu: %zu of %zu frames", shard->index,
                                                 shard->count, owned.size(), job->cameras.size());
  if (absl::GetFlag(FLAGS_check)) return CheckFrames(out_dir, owned, what);

  std::error_code error;
  fs::create_directories(out_dir, error);
  if (error)
    return fail(InputError(absl::InvalidArgumentError(
        absl::StrCat("-o ", out_dir, ": cannot create the folder: ", error.message()))));

  // Every server gets the scene (its textures uploaded when missing); the id is the same on all.
  // A server that cannot be reached is left out; when none can, the addresses were wrong (or
  // every server is down): bad input, like a scene file that cannot be read.
  const std::vector<std::string> servers = ResolveServers(absl::GetFlag(FLAGS_servers));
  std::vector<std::string> ready;
  size_t reached = 0;
  SceneOnServer loaded;
  for (const std::string& server : servers) {
    auto channel = ConnectChannel(server);
    if (!channel.ok()) {
      std::fprintf(stderr, "aperture batch: %s; not used\n",
                   std::string(channel.status().message()).c_str());
      continue;
    }
    ++reached;
    auto stub = v1::Render::NewStub(*channel);
    auto scene = LoadSceneOnServer(*stub, job->scene);
    if (!scene.ok() && IsInputError(scene.status())) return fail(scene.status());
    if (!scene.ok()) {
      std::fprintf(stderr, "aperture batch: %s: %s; not used\n", server.c_str(),
                   std::string(scene.status().message()).c_str());
      continue;
    }
    loaded = *std::move(scene);
    ready.push_back(server);
  }
  if (reached == 0)
    return fail(InputError(absl::UnavailableError(
        absl::StrCat("--servers ", absl::GetFlag(FLAGS_servers), ": no server could be reached"))));
  if (ready.empty()) return fail(absl::UnavailableError("no server could load the scene"));
  auto base = FrameRequestFromFlags(loaded);
  if (!base.ok()) return fail(base.status());

  // gRPC's round_robin policy spreads the frames over the servers the scene was loaded on (the
  // `ipv4:` resolver over those addresses, not `dns:///NAME`: every server must hold the scene
  // before a frame reaches it, and a name resolved again could route frames to a server that
  // joined after the loads). gRPC itself retries UNAVAILABLE (a server gone or restarting) with
  // backoff, and round_robin sends the retry to the next server; the loop below retries what
  // another attempt can fix beyond that (RESOURCE_EXHAUSTED, DEADLINE_EXCEEDED, ...).
  grpc::ChannelArguments args;
  args.SetServiceConfigJSON(R"({
    "loadBalancingConfig": [{"round_robin": {}}],
    "methodConfig": [{
      "name": [{"service": "aperture.v1.Render", "method": "RenderFrame"}],
      "retryPolicy": {"maxAttempts": 4, "initialBackoff": "0.05s", "maxBackoff": "1s",
                      "backoffMultiplier": 2, "retryableStatusCodes": ["UNAVAILABLE"]}}]})");
  auto frames_channel = MakeChannel(absl::StrCat("ipv4:", absl::StrJoin(ready, ",")), args);
  if (!frames_channel.ok()) return fail(frames_channel.status());
  auto stub = v1::Render::NewStub(*frames_channel);

  const size_t frames = owned.size();
  const uint32_t width = base->options().width(), height = base->options().height();
  const int attempts = 3 * static_cast<int>(ready.size());
  std::atomic<size_t> next{0}, rendered{0}, skipped{0}, failed{0}, retries{0};
  const auto start = Clock::now();
  BatchProgress progress(frames, stderr, ::isatty(::fileno(stderr)) != 0);

  std::vector<std::thread> workers;
  for (int w = 0; w < std::max(1, absl::GetFlag(FLAGS_concurrency)); ++w) {
    workers.emplace_back([&] {
      for (size_t k = next++; k < frames; k = next++) {
        const size_t i = owned[k];
        const std::string path = FramePath(out_dir, i);
        if (InvalidFrame(path, width, height).empty()) {
          ++skipped;
          progress.Finish(BatchProgress::Outcome::kSkipped);
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
          const grpc::Status status = stub->RenderFrame(&context, request, &response);
          progress.Attempt(context.peer(), status.ok());
          if (status.ok() && WriteFrame(path, response.exr())) {
            ++rendered;
            progress.Finish(BatchProgress::Outcome::kRendered);
            break;
          }
          // A request the server refused as such fails the same way everywhere: not retried.
          const bool final = !status.ok() && !Retryable(status.error_code());
          if (final || attempt + 1 == attempts) {
            ok = false;
            progress.Note(absl::StrCat("batch: frame ", i, " failed after ", attempt + 1,
                                       " attempt(s): ",
                                       status.ok() ? absl::StrCat("cannot write ", path)
                                                   : absl::StrCat(GrpcCodeName(status.error_code()),
                                                                  ": ", status.error_message())));
            break;
          }
        }
        if (!ok) {
          ++failed;
          progress.Finish(BatchProgress::Outcome::kFailed);
        }
      }
    });
  }
  for (std::thread& t : workers) t.join();
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  progress.Close();
  if (absl::GetFlag(FLAGS_contact_sheet)) WriteSheet(owned, out_dir, *shard);
  std::printf(
      "batch: %s on %zu servers: %zu rendered, %zu skipped (already valid), "
      "%zu failed, %zu retries in %.2f s\n",
      what.c_str(), ready.size(), rendered.load(), skipped.load(), failed.load(), retries.load(),
      seconds);
  return failed == 0 ? 0 : 1;
}

}  // namespace aperture
