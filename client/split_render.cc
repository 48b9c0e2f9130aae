// `aperture render --split K --servers A,B,...`: one frame cut into K bands of equal
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
#include "exit_status.h"
#include "grpc_status.h"
#include "request_flags.h"
#include "scene_upload.h"
// After the protobuf headers: OpenImageIO's byte-swap macros break protobuf's port.h.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
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

// The region's EXR, checked to lie where it was planned: its data window is the region, its
// display window the whole frame (the server writes regions that way).
absl::StatusOr<OIIO::ImageBuf> ReadRegion(const RegionResult& r, const v1::RenderOptions& options) {
  const std::string& exr = r.response.exr();
  OIIO::Filesystem::IOMemReader reader(exr.data(), exr.size());
  OIIO::ImageSpec config;
  void* proxy = &reader;
  config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  auto in = OIIO::ImageInput::open("region.exr", &config, &reader);
  if (!in) return absl::DataLossError("a region's EXR does not open: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  const v1::PixelRegion& region = r.plan.region();
  if (spec.x != static_cast<int>(region.x()) || spec.y != static_cast<int>(region.y()) ||
      spec.width != static_cast<int>(region.width()) ||
      spec.height != static_cast<int>(region.height()) || spec.nchannels != 4 ||
      spec.full_width != static_cast<int>(options.width()) ||
      spec.full_height != static_cast<int>(options.height()))
    return absl::DataLossError(absl::StrCat("region at row ", region.y(), " came back as ",
                                            spec.width, "x", spec.height, "x", spec.nchannels,
                                            " at (", spec.x, ", ", spec.y, ") in a ",
                                            spec.full_width, "x", spec.full_height, " frame"));
  OIIO::ImageBuf image(spec);
  if (!in->read_image(0, 0, 0, 4, spec.format, image.localpixels()))
    return absl::DataLossError("a region's EXR does not decode: " + in->geterror());
  return image;
}

}  // namespace

int RunSplitRender() {
  auto fail = [](const absl::Status& status) { return Fail("render --split", status); };
  const int k = absl::GetFlag(FLAGS_split);
  std::vector<Server> servers;
  const std::vector<std::string> addresses =
      absl::StrSplit(absl::GetFlag(FLAGS_servers), ',', absl::SkipEmpty());
  for (const std::string& address : addresses) {
    auto channel = ConnectChannel(address);
    if (!channel.ok()) return fail(channel.status());
    Server server{address, v1::Render::NewStub(*channel), {}};
    auto scene = LoadSceneOnServer(*server.stub, absl::GetFlag(FLAGS_scene));
    if (!scene.ok()) {
      absl::Status named(scene.status().code(),
                         absl::StrCat(address, ": ", scene.status().message()));
      return fail(IsInputError(scene.status()) ? InputError(named) : named);
    }
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

  // The frame assembled by the regions' data windows (OpenImageIO's paste), with the header of
  // the slowest region: scene, camera, mode and software as every region has them, the render
  // times of the region that decided when the frame was done.
  const v1::RenderOptions& options = request->options();
  OIIO::ImageBuf frame;
  double slowest = 0, sum = 0;
  for (size_t i = 0; i < results.size(); ++i) {
    const RegionResult& r = results[i];
    if (!r.status.ok())
      return fail(absl::Status(r.status.code(),
                               absl::StrCat(servers[r.server].address, ": ", r.status.message())));
    auto region = ReadRegion(r, options);
    if (!region.ok()) return fail(region.status());
    const v1::FrameTimings& t = r.response.timings();
    const double render_ms = t.setup_ms() + t.raster_ms();
    if (i == 0 || render_ms > slowest) {
      OIIO::ImageSpec spec = region->spec();
      spec.x = spec.y = 0;
      spec.width = spec.full_width;
      spec.height = spec.full_height;
      if (i == 0) {
        frame.reset(spec, OIIO::InitializePixels::Yes);
      } else {  // the header only: the pixels stay
        frame.specmod().extra_attribs = spec.extra_attribs;
      }
      slowest = render_ms;
    }
    // OpenImageIO's paste moves the source by the offset given, from where its data window lies:
    // offset 0 puts each region at its place in the frame.
    if (!OIIO::ImageBufAlgo::paste(frame, 0, 0, 0, 0, *region))
      return fail(absl::InternalError("pasting a region: " + frame.geterror()));
    sum += render_ms;
    std::printf(
        "region %zu: rows %u..%u on %s: predicted %.2f ms, render %.2f ms (setup + raster), "
        "encode %.2f ms, round trip %.2f ms\n",
        i, r.plan.region().y(), r.plan.region().y() + r.plan.region().height(),
        servers[r.server].address.c_str(), r.plan.predicted_ms(), render_ms, t.encode_ms(),
        r.round_trip_ms);
  }
  frame.specmod().attribute("aperture:split_regions", static_cast<int>(results.size()));
  const std::string out = absl::GetFlag(FLAGS_o);
  if (!frame.write(out))
    return fail(absl::InternalError(absl::StrCat("cannot write ", out, ": ", frame.geterror())));
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
