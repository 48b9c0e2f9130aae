// `aperture render --split K --servers A,B,...` (issue 6): one frame cut into K bands of equal
// predicted cost by the first server (PlanRegions), the bands rendered at once on the servers in
// turn, and the EXR assembled from them: pixel for pixel the frame one server would render.
#include <grpcpp/grpcpp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "absl/flags/flag.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "aperture/v1/render_service.grpc.pb.h"
#include "channel.h"
#include "client_flags.h"
#include "commands.h"
#include "grpc_status.h"
#include "request_flags.h"
#include "scene_upload.h"
// After the protobuf headers: OpenImageIO's byte-swap macros break protobuf's port.h.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

namespace aperture {
namespace {

using Clock = std::chrono::steady_clock;

struct Server {
  std::string address;
  std::unique_ptr<v1::Render::Stub> stub;
  SceneOnServer scene;
};

struct RegionResult {
  v1::PlannedRegion plan;
  size_t server = 0;
  v1::RenderFrameResponse response;
  absl::Status status;
  double round_trip_ms = 0;
};

// The region's EXR decoded to float RGBA and pasted into `frame` (width x height x 4).
absl::Status Paste(const RegionResult& r, int width, std::vector<float>& frame) {
  const std::string& exr = r.response.exr();
  OIIO::Filesystem::IOMemReader reader(exr.data(), exr.size());
  OIIO::ImageSpec config;
  void* proxy = &reader;
  config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  auto in = OIIO::ImageInput::open("region.exr", &config, &reader);
  if (!in) return absl::DataLossError("a region's EXR does not open: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  const v1::PixelRegion& region = r.plan.region();
  if (spec.width != static_cast<int>(region.width()) ||
      spec.height != static_cast<int>(region.height()) || spec.nchannels != 4)
    return absl::DataLossError(absl::StrCat("region at row ", region.y(), " came back ", spec.width,
                                            "x", spec.height, "x", spec.nchannels));
  std::vector<float> pixels(static_cast<size_t>(spec.width) * spec.height * 4);
  if (!in->read_image(0, 0, 0, 4, OIIO::TypeDesc::FLOAT, pixels.data()))
    return absl::DataLossError("a region's EXR does not decode: " + in->geterror());
  for (int y = 0; y < spec.height; ++y)
    std::copy_n(pixels.begin() + static_cast<ptrdiff_t>(y) * spec.width * 4, spec.width * 4,
                frame.begin() + (static_cast<ptrdiff_t>(region.y() + y) * width + region.x()) * 4);
  return absl::OkStatus();
}

absl::Status WriteFrame(const std::vector<float>& frame, const v1::RenderOptions& options,
                        const std::string& path) {
  OIIO::ImageSpec spec(
      static_cast<int>(options.width()), static_cast<int>(options.height()), 4,
      options.pixel_type() == v1::PIXEL_TYPE_FLOAT ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::HALF);
  spec.attribute("compression", absl::GetFlag(FLAGS_compression));
  spec.attribute("Software", "Aperture (split render)");
  auto out = OIIO::ImageOutput::create(path);
  if (!out || !out->open(path, spec) || !out->write_image(OIIO::TypeDesc::FLOAT, frame.data()) ||
      !out->close())
    return absl::InternalError(
        absl::StrCat("cannot write ", path, ": ", out ? out->geterror() : OIIO::geterror()));
  return absl::OkStatus();
}

}  // namespace

int RunSplitRender() {
  auto fail = [](const absl::Status& status) {
    std::fprintf(stderr, "aperture render --split: error: %s\n",
                 std::string(status.message()).c_str());
    return absl::IsInvalidArgument(status) ? 2 : 1;
  };
  const int k = absl::GetFlag(FLAGS_split);
  std::vector<Server> servers;
  const std::vector<std::string> addresses =
      absl::StrSplit(absl::GetFlag(FLAGS_servers), ',', absl::SkipEmpty());
  for (const std::string& address : addresses) {
    Server server{address, v1::Render::NewStub(MakeChannel(address)), {}};
    auto scene = LoadSceneOnServer(*server.stub, absl::GetFlag(FLAGS_scene));
    if (!scene.ok())
      return fail(absl::Status(scene.status().code(),
                               absl::StrCat(address, ": ", scene.status().message())));
    server.scene = *std::move(scene);
    servers.push_back(std::move(server));
  }
  if (servers.empty()) return fail(absl::InvalidArgumentError("--servers names no server"));
  auto request = FrameRequestFromFlags(servers[0].scene);
  if (!request.ok()) return fail(request.status());
  if (request->has_region())
    return fail(absl::InvalidArgumentError("--region and --split go separately"));

  // The plan, from the first server.
  v1::PlanRegionsRequest plan_request;
  plan_request.set_scene_id(request->scene_id());
  *plan_request.mutable_camera() = request->camera();
  *plan_request.mutable_options() = request->options();
  plan_request.set_regions(static_cast<uint32_t>(k));
  v1::PlanRegionsResponse plan;
  {
    grpc::ClientContext context;
    context.set_deadline(DeadlineIn(60));
    if (auto s = FromGrpcStatus(servers[0].stub->PlanRegions(&context, plan_request, &plan),
                                "PlanRegions");
        !s.ok())
      return fail(s);
  }

  // Every region at once, region i on server i mod n.
  std::vector<RegionResult> results(static_cast<size_t>(plan.regions_size()));
  std::vector<std::thread> threads;
  const auto start = Clock::now();
  for (size_t i = 0; i < results.size(); ++i) {
    results[i].plan = plan.regions(static_cast<int>(i));
    results[i].server = i % servers.size();
    threads.emplace_back([&, i] {
      RegionResult& r = results[i];
      v1::RenderFrameRequest part = *request;
      part.set_scene_id(servers[r.server].scene.scene_id);
      *part.mutable_region() = r.plan.region();
      grpc::ClientContext context;
      context.set_deadline(DeadlineIn(absl::GetFlag(FLAGS_deadline_s)));
      const auto sent = Clock::now();
      r.status = FromGrpcStatus(servers[r.server].stub->RenderFrame(&context, part, &r.response),
                                "RenderFrame");
      r.round_trip_ms = std::chrono::duration<double, std::milli>(Clock::now() - sent).count();
    });
  }
  for (std::thread& t : threads) t.join();
  const double wall_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();

  const v1::RenderOptions& options = request->options();
  std::vector<float> frame(size_t{options.width()} * options.height() * 4, 0.0f);
  double slowest = 0, sum = 0;
  for (size_t i = 0; i < results.size(); ++i) {
    const RegionResult& r = results[i];
    if (!r.status.ok())
      return fail(absl::Status(r.status.code(),
                               absl::StrCat(servers[r.server].address, ": ", r.status.message())));
    if (auto s = Paste(r, static_cast<int>(options.width()), frame); !s.ok()) return fail(s);
    const v1::FrameTimings& t = r.response.timings();
    const double render_ms = t.setup_ms() + t.raster_ms();
    slowest = std::max(slowest, render_ms);
    sum += render_ms;
    std::printf(
        "region %zu: rows %u..%u on %s: predicted %.2f ms, render %.2f ms (setup + raster), "
        "encode %.2f ms, round trip %.2f ms\n",
        i, r.plan.region().y(), r.plan.region().y() + r.plan.region().height(),
        servers[r.server].address.c_str(), r.plan.predicted_ms(), render_ms, t.encode_ms(),
        r.round_trip_ms);
  }
  const std::string out = absl::GetFlag(FLAGS_o);
  if (auto s = WriteFrame(frame, options, out); !s.ok()) return fail(s);
  std::printf(
      "split %ux%u into %zu regions over %zu servers: slowest region %.2f ms, mean %.2f "
      "ms, slowest / mean %.3f; all regions back in %.2f ms\n",
      options.width(), options.height(), results.size(), servers.size(), slowest,
      sum / static_cast<double>(results.size()),
      slowest / (sum / static_cast<double>(results.size())), wall_ms);
  std::printf("wrote %s\n", out.c_str());
  return 0;
}

}  // namespace aperture
