#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>

#include "absl/flags/flag.h"
#include "channel.h"
#include "client_flags.h"
#include "commands.h"
#include "exit_status.h"
#include "grpc_status.h"
#include "request_flags.h"
#include "scene_upload.h"

namespace aperture {

int RunRender() {
  auto fail = [](const absl::Status& status) { return Fail("render", status); };
  if (absl::GetFlag(FLAGS_split) != 0) return RunSplitRender();
  auto channel = ConnectChannel(absl::GetFlag(FLAGS_server));
  if (!channel.ok()) return fail(channel.status());
  auto stub = v1::Render::NewStub(*channel);
  auto scene = LoadSceneOnServer(*stub, absl::GetFlag(FLAGS_scene));
  if (!scene.ok()) return fail(scene.status());
  auto request = FrameRequestFromFlags(*scene);
  if (!request.ok()) return fail(request.status());

  std::printf("scene %s: %u polygons, textures uploaded %d, already on the server %d\n",
              scene->scene_id.substr(0, 12).c_str(), scene->polygons, scene->textures_sent,
              scene->textures_skipped);
  // --repeat: the same frame again on the same connection (warm: HTTP/2 windows grown), one line
  // each; the last one is written.
  v1::RenderFrameResponse response;
  const int repeat = std::max(1, absl::GetFlag(FLAGS_repeat));
  for (int i = 0; i < repeat; ++i) {
    grpc::ClientContext context;
    context.set_deadline(DeadlineIn(absl::GetFlag(FLAGS_deadline_s)));
    const auto start = std::chrono::steady_clock::now();
    if (auto s = FromGrpcStatus(stub->RenderFrame(&context, *request, &response), "RenderFrame");
        !s.ok())
      return fail(s);
    const double round_trip_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const v1::FrameTimings& t = response.timings();
    std::printf(
        "frame %ux%u: queue %.2f ms, setup %.2f ms, raster %.2f ms, encode %.2f ms, "
        "server %.2f ms, round trip %.2f ms\n",
        response.width(), response.height(), t.queue_ms(), t.setup_ms(), t.raster_ms(),
        t.encode_ms(), t.total_ms(), round_trip_ms);
  }

  const std::string out = absl::GetFlag(FLAGS_o);
  std::ofstream file(out, std::ios::binary);
  file.write(response.exr().data(), static_cast<std::streamsize>(response.exr().size()));
  if (!file.flush()) return fail(absl::InternalError("cannot write " + out));
  std::printf("wrote %s (%zu bytes)\n", out.c_str(), response.exr().size());
  return 0;
}

}  // namespace aperture
