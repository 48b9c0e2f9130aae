#include "render_service.h"

#include <malloc.h>
#include <spdlog/fmt/fmt.h>
#include <spdlog/spdlog.h>

#include <string>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "content_hash.h"
#include "frame/render_frame_job.h"
#include "frame_request.h"
#include "log_text.h"
#include "region_plan_request.h"
#include "rpc_calls.h"
#include "scene_id.h"
#include "scene_request.h"
#include "status_mapping.h"
#include "stop_check.h"

namespace aperture {
namespace {

constexpr size_t kMaxChunkBytes = 1 << 20;

using Clock = std::chrono::steady_clock;

double MillisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

std::string Short(const std::string& id) { return id.substr(0, 12); }

const char* ModeName(const v1::RenderOptions& options) {
  return options.mode() == v1::RENDER_MODE_RAYTRACE ? "raytrace" : "raster";
}

std::string ErrorText(const absl::Status& status) {
  return status.ok() ? "" : absl::StrCat(" error='", LogText(status.message()), "'");
}

// A raytraced frame whose summed-area tables the store's budget refused (the engine's message
// names the tables' size, the budget and its flag), counted as such in the refusal log.
absl::Status StoreBudgetRefusal(const absl::Status& status) {
  return absl::IsResourceExhausted(status) && absl::StrContains(status.message(), "--max-store-mb")
             ? MarkRefusal(status, kStoreBudgetRefusal)
             : status;
}

}  // namespace

RenderService::RenderService(const ServiceLimits& limits, TextureStore& textures,
                             SceneStore& scenes, AdmissionControl& admission,
                             tbb::task_arena& arena, const AuthTokens* auth)
    : limits_(limits),
      textures_(textures),
      scenes_(scenes),
      admission_(admission),
      arena_(arena),
      traced_(kTracedScenes, textures.shared(), limits.max_store_bytes),
      uploads_in_flight_("uploads in flight (--max-upload-inflight-mb)",
                         limits.max_upload_inflight_bytes),
      upload_watchdog_(limits.upload_idle),
      calls_(auth) {}

grpc::Status RenderService::HasTexture(grpc::ServerContext* context,
                                       const v1::HasTextureRequest* request,
                                       v1::HasTextureResponse* response) {
  return calls_.Quiet(context, "HasTexture", [&]() -> absl::Status {
    if (!IsSha256Hex(request->sha256()))
      return absl::InvalidArgumentError("sha256 must be 64 lowercase hex digits");
    response->set_stored(textures_.Has(request->sha256()));
    return absl::OkStatus();
  });
}

grpc::Status RenderService::UploadTexture(grpc::ServerContext* context,
                                          grpc::ServerReader<v1::UploadTextureRequest>* reader,
                                          v1::UploadTextureResponse* response) {
  return calls_.Logged(context, "UploadTexture", "upload", [&](RpcCall& call) {
    std::string sha256;
    bool skipped = false;
    const absl::Status status = Upload(context, reader, response, sha256, skipped);
    call.fields = fmt::format("sha256={} bytes={} skipped={} ms={:.2f}", LogText(Short(sha256)),
                              response->size(), skipped, call.Milliseconds());
    return status;
  });
}

absl::Status RenderService::Upload(grpc::ServerContext* context,
                                   grpc::ServerReader<v1::UploadTextureRequest>* reader,
                                   v1::UploadTextureResponse* response, std::string& sha256,
                                   bool& skipped) {
  v1::UploadTextureRequest message;
  if (!reader->Read(&message)) return absl::InvalidArgumentError("upload stream has no message");
  sha256 = message.sha256();
  if (!IsSha256Hex(sha256))
    return absl::InvalidArgumentError("sha256 (first message) must be 64 lowercase hex digits");
  if (message.total_size() > limits_.max_texture_bytes)
    return absl::InvalidArgumentError(
        absl::StrCat("total_size ", message.total_size(), " exceeds the server's limit of ",
                     limits_.max_texture_bytes, " bytes (--max-texture-mb)"));
  response->set_sha256(sha256);
  if (textures_.Has(sha256)) {
    response->set_already_stored(true);
    response->set_size(message.total_size());
    skipped = true;
    return absl::OkStatus();
  }
  const uint64_t total = message.total_size();
  // The announced bytes are reserved before they are allocated, and held while they stream.
  auto reservation = uploads_in_flight_.Reserve(total);
  if (!reservation.ok()) return reservation.status();
  std::unique_ptr<IdleWatchdog::Watch> watch = upload_watchdog_.Start(context);
  std::string content;
  content.reserve(total);
  do {
    watch->Touch();
    if (message.chunk().size() > kMaxChunkBytes)
      return absl::InvalidArgumentError(
          absl::StrCat("chunk of ", message.chunk().size(), " bytes exceeds 1 MiB"));
    if (content.size() + message.chunk().size() > total)
      return absl::InvalidArgumentError(absl::StrCat("chunk: more bytes than total_size ", total));
    content += message.chunk();
  } while (reader->Read(&message));
  const bool idle = watch->Expired();
  watch.reset();  // what follows (checks, the store) is the server's time, not the client's
  if (idle)
    return absl::DeadlineExceededError(absl::StrCat(
        "upload idle for ", upload_watchdog_.idle_limit().count() / 1000.0, " s after ",
        content.size(), " of ", total, " bytes; cancelled and its bytes freed (--upload-idle-s)"));
  if (content.size() != total || content.empty())
    return absl::InvalidArgumentError(
        absl::StrCat("total_size: announced ", total, " bytes, received ", content.size()));
  response->set_size(content.size());
  return textures_.Put(sha256, std::move(content));
}

grpc::Status RenderService::LoadScene(grpc::ServerContext* context,
                                      const v1::LoadSceneRequest* request,
                                      v1::LoadSceneResponse* response) {
  return calls_.Logged(context, "LoadScene", "scene load",
                       [&](RpcCall& call) { return Load(context, *request, response, call); });
}

absl::Status RenderService::Load(grpc::ServerContext* context, const v1::LoadSceneRequest& request,
                                 v1::LoadSceneResponse* response, RpcCall& call) {
  // A request loaded before (a built-in scene by name, a farm job's scene per frame) is answered
  // from the scene store: the same request bytes are the same scene.
  const std::string scene_id = SceneRequestId(request);
  StopCheck stop(context);  // the call's deadline and cancellation, asked while building
  absl::StatusOr<LoadedScene> loaded;
  LoadedScene cached{scene_id, nullptr, std::nullopt};
  cached.scene = scenes_.Find(scene_id, &cached.default_camera);
  const bool reused = cached.scene != nullptr;
  if (reused) loaded = std::move(cached);
  ByteReservation room;  // the scene's estimated bytes in the loaded scenes' budget
  auto admit = [&](const SceneMemory& memory) -> absl::Status {
    if (textures_.shared() && memory.table_bytes > limits_.max_store_bytes)
      return MarkRefusal(absl::ResourceExhaustedError(absl::StrCat(
                             "the scene's seed 000 tables would take ", memory.table_bytes >> 20,
                             " MiB of the texture store, above its budget of ",
                             limits_.max_store_bytes >> 20, " MiB (--max-store-mb)")),
                         kStoreBudgetRefusal);
    auto reserved = scenes_.Reserve(memory.total(), memory.ToString());
    if (!reserved.ok()) return reserved.status();
    room = *std::move(reserved);
    return absl::OkStatus();
  };
  if (!reused)
    loaded = BuildSceneFromRequest(
        request, textures_, limits_.scene, [&] { return stop(); }, admit);
  if (absl::IsCancelled(loaded.status()) && stop.DeadlinePassed())
    loaded = absl::DeadlineExceededError(
        "the call's deadline passed while the scene was built; nothing was kept");
  if (loaded.ok()) {
    // The tables it built made room for themselves in the store (TextureStore::SetBudget).
    if (!reused) scenes_.Put(loaded->id, loaded->scene, loaded->default_camera, std::move(room));
    response->set_scene_id(loaded->id);
    response->set_polygons(static_cast<uint32_t>(loaded->scene->polygons.size()));
    response->set_textures(static_cast<uint32_t>(loaded->scene->textures.size()));
    response->set_build_ms(call.Milliseconds());
    if (loaded->default_camera) *response->mutable_default_camera() = *loaded->default_camera;
    for (const SceneObject& object : loaded->scene->objects) {
      v1::NamedObject& named = *response->add_objects();
      named.set_name(object.name);
      *named.mutable_transform() = object.transform;
      named.set_hidden(!object.visible);
    }
  }
  call.fields =
      fmt::format("scene={}{} name='{}' ms={:.2f}", loaded.ok() ? Short(loaded->id) : "-",
                  reused ? " (loaded before)" : "",
                  LogText(request.builtin_scene().empty() ? request.scene().name()
                                                          : "builtin:" + request.builtin_scene()),
                  call.Milliseconds());
  return loaded.status();
}

absl::StatusOr<EncodeFrameFn> RenderService::RenderImage(grpc::ServerContext* context,
                                                         const v1::RenderFrameRequest& request,
                                                         LiveScene& live,
                                                         std::shared_ptr<const Scene> stored,
                                                         LiveClock::time_point stop_at,
                                                         v1::RenderFrameResponse* response) {
  const auto start = Clock::now();
  response->set_frame_index(request.frame_index());
  auto job = ParseFrameRequest(request, limits_.max_pixels,
                               FrameJobOptions{.max_frame_bytes = limits_.max_frame_bytes});
  if (!job.ok()) return job.status();
  StopCheck stop(context, stop_at);
  // Before admission: the update holds from this frame on even if the frame is refused.
  const auto update_start = Clock::now();
  auto live_scene = live.Advance(request, std::move(stored), [&] { return stop(); });
  if (!live_scene.ok())
    return WhyStopped(live_scene.status(), stop, "while its scene update was applied");
  const std::shared_ptr<const Scene> scene = *std::move(live_scene);
  const bool updated = live.updated();
  const double update_ms = MillisecondsSince(update_start);

  auto ticket = admission_.Enter([&] { return stop(); });
  // The waiter leaves the queue within milliseconds of its deadline, and says which it was.
  if (!ticket.ok())
    return absl::IsCancelled(ticket.status()) && stop.DeadlinePassed()
               ? absl::DeadlineExceededError(stop.FrameDeadlinePassed()
                                                 ? "the frame's deadline_ms passed in the queue"
                                                 : "the call's deadline passed in the queue")
               : ticket.status();
  v1::FrameTimings& timings = *response->mutable_timings();
  timings.set_update_ms(update_ms);
  timings.set_queue_ms(MillisecondsSince(start) - update_ms);

  auto frame = std::make_shared<absl::StatusOr<RenderedFrame>>();
  double traced_build_ms = 0;
  // seed 003: the scene's BVH and tables on its first raytraced frame, then corner rays. A
  // channel's updated scene has its own, built for this frame (the tables come from the store
  // when there is one).
  const TracedSceneSource traced = [&]() -> absl::StatusOr<std::shared_ptr<const TracedScene>> {
    if (!updated) {
      auto cached =
          traced_.Get(request.scene_id(), scene, &traced_build_ms, [&] { return stop(); });
      if (!cached.ok()) return StoreBudgetRefusal(cached.status());
      return cached;
    }
    const auto build_start = Clock::now();
    auto built = TracedScene::Build(
        *scene, textures_.shared(), [&] { return stop(); }, limits_.max_store_bytes);
    traced_build_ms = MillisecondsSince(build_start);
    if (!built.ok()) return StoreBudgetRefusal(built.status());
    return std::shared_ptr<const TracedScene>(*std::move(built));
  };
  arena_.execute([&] {
    // Isolated: while this thread waits for its frame's tasks it takes none of another frame's,
    // so a small frame is not held up behind a big one's work.
    tbb::this_task_arena::isolate([&] {
      try {
        *frame = RenderFrameJob(*scene, *job, traced, [&] { return stop(); });
      } catch (const std::exception& e) {
        // Never UNKNOWN "Unexpected error in RPC handling": the frame fails with what happened.
        *frame = absl::InternalError(absl::StrCat("the frame failed: ", e.what()));
      }
    });
  });
  if (!frame->ok())
    return stop.DeadlinePassed() && absl::IsCancelled(frame->status())
               ? absl::DeadlineExceededError(stop.FrameDeadlinePassed()
                                                 ? "the frame's deadline_ms passed while rendering"
                                                 : "the call's deadline passed while rendering")
               : frame->status();
  // Raytrace: setup is the corner rays (plus building the scene's BVH and tables on its first
  // raytraced frame), raster the pixels' fragments and subdivision.
  timings.set_setup_ms((*frame)->stats.setup_ms + traced_build_ms);
  timings.set_raster_ms((*frame)->stats.raster_ms);
  ExrOptions exr = job->exr;
  exr.metadata = FrameJobMetadata(scene->name, *job, **frame);
  return EncodeFrameFn([this, frame, exr, start](v1::RenderFrameResponse* out) -> absl::Status {
    const auto encode_start = Clock::now();
    // Compressed in parallel on the render arena's threads: encode and render share the cores.
    absl::StatusOr<std::string> bytes;
    arena_.execute(
        [&] { tbb::this_task_arena::isolate([&] { bytes = EncodeExr((*frame)->image, exr); }); });
    if (!bytes.ok()) return bytes.status();
    v1::FrameTimings& out_timings = *out->mutable_timings();
    out_timings.set_encode_ms(MillisecondsSince(encode_start));
    out->set_exr(std::move(*bytes));
    out->set_width(static_cast<uint32_t>((*frame)->image.width()));
    out->set_height(static_cast<uint32_t>((*frame)->image.height()));
    out_timings.set_total_ms(MillisecondsSince(start));
    return absl::OkStatus();
  });
}

absl::Status RenderService::RenderOne(grpc::ServerContext* context,
                                      const v1::RenderFrameRequest& request,
                                      v1::RenderFrameResponse* response) {
  LiveScene live(scenes_);  // the request's update applies to this frame only
  auto encode =
      RenderImage(context, request, live, nullptr, LiveClock::time_point::max(), response);
  if (!encode.ok()) return encode.status();
  return (*encode)(response);
}

grpc::Status RenderService::RenderFrame(grpc::ServerContext* context,
                                        const v1::RenderFrameRequest* request,
                                        v1::RenderFrameResponse* response) {
  return calls_.Logged(context, "RenderFrame", "frame", [&](RpcCall& call) {
    const absl::Status status = RenderOne(context, *request, response);
    (status.ok() ? frames_rendered_ : frames_failed_)++;
    const v1::FrameTimings& t = response->timings();
    call.fields = fmt::format(
        "scene={} size={}x{} mode={} queue_ms={:.2f} setup_ms={:.2f} raster_ms={:.2f} "
        "encode_ms={:.2f} total_ms={:.2f} bytes={}",
        LogText(Short(request->scene_id())), request->options().width(),
        request->options().height(), ModeName(request->options()), t.queue_ms(), t.setup_ms(),
        t.raster_ms(), t.encode_ms(), call.Milliseconds(), response->exr().size());
    if (!status.ok()) response->Clear();
    return status;
  });
}

grpc::Status RenderService::RenderStream(
    grpc::ServerContext* context,
    grpc::ServerReaderWriter<v1::RenderFrameResponse, v1::RenderFrameRequest>* stream) {
  return calls_.Logged(context, "RenderStream", "stream",
                       [&](RpcCall& call) { return Stream(context, stream, call); });
}

absl::Status RenderService::Stream(
    grpc::ServerContext* context,
    grpc::ServerReaderWriter<v1::RenderFrameResponse, v1::RenderFrameRequest>* stream,
    RpcCall& call) {
  const uint64_t id = call.id;
  // The stream's scene state: updates apply from their frame on, for this stream only. It holds
  // the stream's scene from its first request on, so the scene store does not drop it.
  LiveScene live(scenes_);
  auto check = [&](const v1::RenderFrameRequest& request, const std::function<bool()>& stop) {
    return live.Check(request, stop);
  };
  auto render = [&](const v1::RenderFrameRequest& request, std::shared_ptr<const Scene> scene,
                    LiveClock::time_point stop_at, v1::RenderFrameResponse* response) {
    return RenderImage(context, request, live, std::move(scene), stop_at, response);
  };
  auto answered = [&](const LiveAnswer& answer) {
    const LiveRequestSummary& request = answer.summary;
    const v1::RenderFrameResponse& response = answer.response;
    const v1::FrameTimings& t = response.timings();
    if (response.outcome() != v1::FRAME_OUTCOME_RENDERED) {
      frames_skipped_++;
      spdlog::info("req={}.{} rpc=RenderStream skipped={} superseded_by={} total_ms={:.2f}", id,
                   answer.frame_index,
                   response.outcome() == v1::FRAME_OUTCOME_SKIPPED_LATE ? "late" : "superseded",
                   response.superseded_by(), MillisecondsSince(answer.received));
      return;
    }
    (answer.status.ok() ? frames_rendered_ : frames_failed_)++;
    calls_.Log(
        answer.status, "frame",
        fmt::format("req={}.{} rpc=RenderStream scene={} size={}x{} mode={} "
                    "wait_ms={:.2f} update_ms={:.3f} queue_ms={:.2f} setup_ms={:.2f} "
                    "raster_ms={:.2f} hold_ms={:.2f} encode_ms={:.2f} total_ms={:.2f} bytes={} "
                    "status={}{}",
                    id, answer.frame_index, LogText(Short(request.scene_id)), request.width,
                    request.height,
                    request.mode == v1::RENDER_MODE_RAYTRACE ? "raytrace" : "raster", t.wait_ms(),
                    t.update_ms(), t.queue_ms(), t.setup_ms(), t.raster_ms(), t.hold_ms(),
                    t.encode_ms(), MillisecondsSince(answer.received), response.exr().size(),
                    absl::StatusCodeToString(answer.status.code()), ErrorText(answer.status)));
  };
  const LiveStreamCounts counts = LiveStream(context, stream, check, render, answered).Run();
  // What the stream's threads allocated (requests, answers, frames) glibc keeps in its arenas
  // after they are freed, as the trim threshold is raised to keep frame buffers warm: given back
  // here, the server's RSS returns to within a few MB of where it was (about 1 ms).
  malloc_trim(0);
  call.fields = fmt::format("frames={} rendered={} skipped={} failed={} ms={:.2f}", counts.frames,
                            counts.rendered, counts.skipped, counts.failed, call.Milliseconds());
  return context->IsCancelled() ? absl::CancelledError() : absl::OkStatus();
}

grpc::Status RenderService::PlanRegions(grpc::ServerContext* context,
                                        const v1::PlanRegionsRequest* request,
                                        v1::PlanRegionsResponse* response) {
  return calls_.Logged(context, "PlanRegions", "plan", [&](RpcCall& call) {
    absl::Status status = CheckSceneId(request->scene_id());
    if (status.ok()) {
      std::shared_ptr<const Scene> scene = scenes_.Find(request->scene_id());
      status = scene ? PlanRegionsForRequest(*scene, *request, limits_.max_pixels, response)
                     : absl::NotFoundError(absl::StrCat("scene_id '", request->scene_id(),
                                                        "' is not loaded (LoadScene first)"));
    }
    call.fields = fmt::format("scene={} size={}x{} regions={} ms={:.2f}",
                              LogText(Short(request->scene_id())), request->options().width(),
                              request->options().height(), request->regions(), call.Milliseconds());
    if (!status.ok()) response->Clear();
    return status;
  });
}

grpc::Status RenderService::GetServerInfo(grpc::ServerContext* context,
                                          const v1::GetServerInfoRequest*,
                                          v1::GetServerInfoResponse* response) {
  return calls_.Quiet(context, "GetServerInfo", [&] {
    ServerInfo(response);
    return absl::OkStatus();
  });
}

void RenderService::ServerInfo(v1::GetServerInfoResponse* response) const {
  response->set_version(APERTURE_VERSION);  // CMake's project version
  response->set_threads(static_cast<uint32_t>(limits_.threads));
  response->set_max_queue(static_cast<uint32_t>(limits_.max_queue));
  response->set_concurrent_frames(static_cast<uint32_t>(limits_.concurrent_frames));
  response->set_max_pixels(limits_.max_pixels);
  response->set_max_message_bytes(limits_.max_message_bytes);
  response->set_scenes(static_cast<uint32_t>(scenes_.size()));
  response->set_textures(static_cast<uint32_t>(textures_.size()));
  response->set_frames_rendered(frames_rendered_.load());
  response->set_frames_failed(frames_failed_.load());
  response->set_frames_skipped(frames_skipped_.load());
  response->set_frames_rejected(admission_.rejected());
  response->set_frames_in_flight(static_cast<uint32_t>(admission_.running()));
  response->set_frames_queued(static_cast<uint32_t>(admission_.queued()));
  response->set_uptime_s(std::chrono::duration<double>(Clock::now() - started_).count());
  v1::Budgets& budgets = *response->mutable_budgets();
  budgets.set_scene_bytes(scenes_.bytes());
  budgets.set_scene_budget_bytes(scenes_.budget());
  budgets.set_scenes_evicted(scenes_.evicted());
  budgets.set_upload_bytes_in_flight(uploads_in_flight_.used());
  budgets.set_upload_budget_bytes(uploads_in_flight_.limit());
  budgets.set_store_bytes(textures_.bytes());
  budgets.set_store_budget_bytes(limits_.max_store_bytes);
  budgets.set_store_entries_evicted(textures_.evicted());
  if (const auto& store = textures_.shared()) {
    const StoreCounters counters = store->counters();
    v1::StoreInfo& info = *response->mutable_store();
    info.set_directory(store->directory());
    info.set_entries_attached(counters.attached);
    info.set_entries_built(counters.built);
    info.set_entries_rejected(counters.rejected);
  }
}

}  // namespace aperture
