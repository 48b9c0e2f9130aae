// Hostile live streams against a running aperture-server on loopback (scripts/bench-hostile.sh
// samples the server's RSS around it). Two cases:
//   --case unread-streams  N RenderStream clients send small valid requests of the demo scene for
//                          S seconds and never read an answer, then cancel;
//   --case big-update      on a scene of --objects named objects, one stream frame whose update
//                          names every object once, then one whose update names one object
//                          --objects times.
//   --case one-spot        on a scene of --objects named objects, one stream frame whose update
//                          moves every object to one spot of the ground, then a 1920x1080 frame.
// Prints what each case did and how long it took; with --server-pid, also the server's VmRSS
// before, at the end of the sending and a few seconds after the cancel.
// Usage: hostile_streams --server HOST:PORT --case unread-streams|big-update|one-spot [--streams 2]
//        [--seconds 30] [--objects 100000] [--deadline-s 300] [--server-pid PID]
#include <grpcpp/grpcpp.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "aperture/v1/render_service.grpc.pb.h"
#include "support/hostile_inputs.h"

namespace aperture {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The server's resident set in MiB, or -1 without a pid (or when it cannot be read).
double ServerRssMb(int pid) {
  if (pid <= 0) return -1;
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string key;
  while (status >> key) {
    if (key == "VmRSS:") {
      double kb = 0;
      status >> kb;
      return kb / 1024;
    }
    status.ignore(1 << 12, '\n');
  }
  return -1;
}

void PrintRss(int pid, const char* when) {
  if (pid > 0) std::printf("server VmRSS %s: %.1f MiB\n", when, ServerRssMb(pid));
}

struct Options {
  std::string server = "127.0.0.1:50051";
  std::string which;
  int streams = 2;
  double seconds = 30;
  int objects = 100000;
  double deadline_s = 300;
  int server_pid = 0;
};

class Bench {
 public:
  explicit Bench(const Options& options) : options_(options) {
    grpc::ChannelArguments args;
    args.SetMaxReceiveMessageSize(-1);
    channel_ = grpc::CreateCustomChannel(options.server, grpc::InsecureChannelCredentials(), args);
    stub_ = v1::Render::NewStub(channel_);
  }

  int UnreadStreams() {
    v1::LoadSceneRequest load;
    load.set_builtin_scene("demo");
    v1::LoadSceneResponse loaded;
    if (!Load(load, &loaded)) return 2;
    v1::RenderFrameRequest request;
    request.set_scene_id(loaded.scene_id());
    *request.mutable_camera() = loaded.default_camera();
    request.mutable_options()->set_width(64);
    request.mutable_options()->set_height(48);
    {  // one frame first, so that the figures leave out what the scene's first frame builds
      grpc::ClientContext context;
      SetDeadline(&context);
      v1::RenderFrameResponse response;
      const grpc::Status status = stub_->RenderFrame(&context, request, &response);
      if (!status.ok()) {
        std::fprintf(stderr, "hostile_streams: RenderFrame: %s %s\n", StatusName(status).c_str(),
                     status.error_message().c_str());
        return 2;
      }
    }
    PrintRss(options_.server_pid, "before the streams");
    struct Unread {
      grpc::ClientContext context;
      std::unique_ptr<grpc::ClientReaderWriter<v1::RenderFrameRequest, v1::RenderFrameResponse>>
          stream;
      std::atomic<uint64_t> written{0};
      std::atomic<double> longest_write_s{0};
    };
    std::vector<std::unique_ptr<Unread>> streams;
    std::vector<std::thread> writers;
    const auto start = Clock::now();
    for (int s = 0; s < options_.streams; ++s) {
      auto unread = std::make_unique<Unread>();
      unread->stream = stub_->RenderStream(&unread->context);
      Unread* u = unread.get();
      writers.emplace_back([u, request]() mutable {
        for (uint64_t i = 0;; ++i) {
          request.set_frame_index(i);
          const auto write_start = Clock::now();
          if (!u->stream->Write(request)) break;  // cancelled, or the server ended the stream
          const double took = SecondsSince(write_start);
          if (took > u->longest_write_s) u->longest_write_s = took;
          u->written = i + 1;
        }
      });
      streams.push_back(std::move(unread));
    }
    std::this_thread::sleep_for(std::chrono::duration<double>(options_.seconds));
    PrintRss(options_.server_pid, "after the sending");
    for (auto& u : streams) u->context.TryCancel();
    for (std::thread& t : writers) t.join();
    const double sent_s = SecondsSince(start);
    for (size_t s = 0; s < streams.size(); ++s) {
      const grpc::Status status = streams[s]->stream->Finish();
      std::printf(
          "stream %zu: %llu requests written in %.1f s, longest write %.2f s, ended %s%s%s\n", s,
          static_cast<unsigned long long>(streams[s]->written.load()), sent_s,
          streams[s]->longest_write_s.load(), StatusName(status).c_str(),
          status.error_message().empty() ? "" : ": ", status.error_message().c_str());
    }
    for (int wait = 1; wait <= 3; ++wait) {
      std::this_thread::sleep_for(std::chrono::seconds(1));
      PrintRss(options_.server_pid, (std::to_string(wait) + " s after the cancel").c_str());
    }
    return 0;
  }

  int BigUpdate() {
    v1::LoadSceneRequest load;
    *load.mutable_scene() = testing::ManyObjectsScene(options_.objects);
    const auto load_start = Clock::now();
    v1::LoadSceneResponse loaded;
    if (!Load(load, &loaded)) return 2;
    std::printf("scene of %d objects loaded in %.2f s (%u polygons)\n", options_.objects,
                SecondsSince(load_start), loaded.polygons());
    PrintRss(options_.server_pid, "after the load");
    int failures = 0;
    failures += !UpdateFrame(loaded.scene_id(), testing::UpdateEveryObject(options_.objects),
                             "every object named once");
    failures += !UpdateFrame(loaded.scene_id(),
                             testing::UpdateOneObjectRepeatedly(options_.objects, options_.objects),
                             "one object named every time");
    PrintRss(options_.server_pid, "after the updates");
    return failures == 0 ? 0 : 1;
  }

  int OneSpot() {
    v1::LoadSceneRequest load;
    *load.mutable_scene() = testing::ManyObjectsScene(options_.objects);
    v1::LoadSceneResponse loaded;
    if (!Load(load, &loaded)) return 2;
    PrintRss(options_.server_pid, "after the load");
    v1::RenderFrameRequest request;
    request.set_scene_id(loaded.scene_id());
    request.mutable_camera()->mutable_position()->set_y(3);
    request.mutable_camera()->set_pitch_deg(-60);
    request.mutable_options()->set_width(64);
    request.mutable_options()->set_height(48);
    for (int i = 0; i < options_.objects; ++i) {
      v1::ObjectUpdate& o = *request.mutable_update()->add_objects();
      o.set_name("object-" + std::to_string(i));
      o.mutable_transform()->mutable_translation()->set_z(-2);
    }
    grpc::ClientContext context;
    SetDeadline(&context);
    auto stream = stub_->RenderStream(&context);
    int failures = 0;
    for (const auto& [width, height] : {std::pair{64, 48}, {1920, 1080}}) {
      request.mutable_options()->set_width(width);
      request.mutable_options()->set_height(height);
      const auto start = Clock::now();
      v1::RenderFrameResponse response;
      const bool answered = stream->Write(request) && stream->Read(&response);
      std::printf("%dx%d frame%s: round trip %.3f s, server raster %.1f ms, status %d%s%s\n", width,
                  height, request.has_update() ? " moving every object to one spot" : "",
                  SecondsSince(start), response.timings().raster_ms(), response.status_code(),
                  response.status_message().empty() ? "" : ": ", response.status_message().c_str());
      failures += !answered || response.status_code() != 0;
      request.clear_update();
    }
    stream->WritesDone();
    failures += !stream->Finish().ok();
    PrintRss(options_.server_pid, "after the frames");
    return failures == 0 ? 0 : 1;
  }

 private:
  static std::string StatusName(const grpc::Status& status) {
    static const char* const kNames[] = {"OK",
                                         "CANCELLED",
                                         "UNKNOWN",
                                         "INVALID_ARGUMENT",
                                         "DEADLINE_EXCEEDED",
                                         "NOT_FOUND",
                                         "ALREADY_EXISTS",
                                         "PERMISSION_DENIED",
                                         "RESOURCE_EXHAUSTED",
                                         "FAILED_PRECONDITION",
                                         "ABORTED",
                                         "OUT_OF_RANGE",
                                         "UNIMPLEMENTED",
                                         "INTERNAL",
                                         "UNAVAILABLE",
                                         "DATA_LOSS",
                                         "UNAUTHENTICATED"};
    const int code = static_cast<int>(status.error_code());
    return code >= 0 && code <= 16 ? kNames[code] : std::to_string(code);
  }

  void SetDeadline(grpc::ClientContext* context) const {
    context->set_deadline(
        std::chrono::system_clock::now() +
        std::chrono::milliseconds(static_cast<int64_t>(options_.deadline_s * 1e3)));
  }

  bool Load(const v1::LoadSceneRequest& request, v1::LoadSceneResponse* response) {
    grpc::ClientContext context;
    SetDeadline(&context);
    const grpc::Status status = stub_->LoadScene(&context, request, response);
    if (!status.ok())
      std::fprintf(stderr, "hostile_streams: LoadScene: %s %s\n", StatusName(status).c_str(),
                   status.error_message().c_str());
    return status.ok();
  }

  // One stream frame of `scene_id` carrying `update`: the round trip and the server's update_ms.
  bool UpdateFrame(const std::string& scene_id, const v1::SceneUpdate& update, const char* what) {
    v1::RenderFrameRequest request;
    request.set_scene_id(scene_id);
    request.mutable_camera()->mutable_position()->set_y(30);
    request.mutable_camera()->set_pitch_deg(-30);
    request.mutable_options()->set_width(32);
    request.mutable_options()->set_height(32);
    *request.mutable_update() = update;
    grpc::ClientContext context;
    SetDeadline(&context);
    const auto start = Clock::now();
    auto stream = stub_->RenderStream(&context);
    v1::RenderFrameResponse response;
    const bool answered = stream->Write(request) && stream->Read(&response);
    const double round_trip_s = SecondsSince(start);
    stream->WritesDone();
    const grpc::Status status = stream->Finish();
    std::printf(
        "update, %s (%d entries, %.1f MB): round trip %.2f s, server update_ms %.1f, frame "
        "status %d%s%s, stream %s\n",
        what, update.objects_size(), update.ByteSizeLong() / 1e6, round_trip_s,
        response.timings().update_ms(), response.status_code(),
        response.status_message().empty() ? "" : ": ", response.status_message().c_str(),
        StatusName(status).c_str());
    return answered && response.status_code() == 0 && status.ok();
  }

  const Options options_;
  std::shared_ptr<grpc::Channel> channel_;
  std::unique_ptr<v1::Render::Stub> stub_;
};

}  // namespace
}  // namespace aperture

int main(int argc, char** argv) {
  aperture::Options options;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i], value = argv[i + 1];
    if (flag == "--server")
      options.server = value;
    else if (flag == "--case")
      options.which = value;
    else if (flag == "--streams")
      options.streams = std::atoi(value.c_str());
    else if (flag == "--seconds")
      options.seconds = std::atof(value.c_str());
    else if (flag == "--objects")
      options.objects = std::atoi(value.c_str());
    else if (flag == "--deadline-s")
      options.deadline_s = std::atof(value.c_str());
    else if (flag == "--server-pid")
      options.server_pid = std::atoi(value.c_str());
    else {
      std::fprintf(stderr, "hostile_streams: unknown flag %s\n", flag.c_str());
      return 2;
    }
  }
  if (options.server.rfind("127.", 0) != 0 && options.server.rfind("localhost", 0) != 0) {
    std::fprintf(stderr, "hostile_streams: loopback servers only (127.0.0.0/8, localhost)\n");
    return 2;
  }
  aperture::Bench bench(options);
  if (options.which == "unread-streams") return bench.UnreadStreams();
  if (options.which == "big-update") return bench.BigUpdate();
  if (options.which == "one-spot") return bench.OneSpot();
  std::fprintf(
      stderr,
      "usage: hostile_streams --server HOST:PORT --case unread-streams|big-update|one-spot "
      "[--streams N] [--seconds S] [--objects N] [--deadline-s S] [--server-pid PID]\n");
  return 2;
}
