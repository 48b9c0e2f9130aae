// The aperture.v1.Render service: validates each request, hands it to the engine and answers with
// the engine's status. What every call does around that (the token check, the request id, the
// log line, refusals at most a line a second per kind) is rpc_calls.h's.
#pragma once

#include <tbb/task_arena.h>

#include <atomic>
#include <chrono>
#include <cstdint>

#include "admission.h"
#include "aperture/v1/render_service.grpc.pb.h"
#include "auth_tokens.h"
#include "byte_budget.h"
#include "idle_watchdog.h"
#include "live_scene.h"
#include "live_stream.h"
#include "refusal_log.h"
#include "rpc_calls.h"
#include "scene/scene_builder.h"
#include "scene_store.h"
#include "texture_store.h"
#include "traced_scene_cache.h"

namespace aperture {

struct ServiceLimits {
  uint64_t max_pixels = 4096ull * 4096;
  uint64_t max_texture_bytes = 256ull << 20;
  uint64_t max_message_bytes = 64ull << 20;
  int threads = 1;
  int concurrent_frames = 2;
  int max_queue = 16;
  SceneLimits scene;                                // what one LoadScene may ask for
  uint64_t max_upload_inflight_bytes = 1ull << 30;  // announced sizes of uploads streaming now
  std::chrono::milliseconds upload_idle{30000};     // an upload silent this long is cancelled
  uint64_t max_store_bytes = 8ull << 30;  // the texture store's entries (or in-memory uploads)
  uint64_t max_frame_bytes = 0;  // one frame's working memory (render/frame_memory.h); 0: none
};

class RenderService final : public v1::Render::Service {
 public:
  RenderService(const ServiceLimits& limits, TextureStore& textures, SceneStore& scenes,
                AdmissionControl& admission, tbb::task_arena& arena,
                const AuthTokens* auth = nullptr);  // null: no authentication

  grpc::Status HasTexture(grpc::ServerContext* context, const v1::HasTextureRequest* request,
                          v1::HasTextureResponse* response) override;
  grpc::Status UploadTexture(grpc::ServerContext* context,
                             grpc::ServerReader<v1::UploadTextureRequest>* reader,
                             v1::UploadTextureResponse* response) override;
  grpc::Status LoadScene(grpc::ServerContext* context, const v1::LoadSceneRequest* request,
                         v1::LoadSceneResponse* response) override;
  grpc::Status RenderFrame(grpc::ServerContext* context, const v1::RenderFrameRequest* request,
                           v1::RenderFrameResponse* response) override;
  grpc::Status RenderStream(
      grpc::ServerContext* context,
      grpc::ServerReaderWriter<v1::RenderFrameResponse, v1::RenderFrameRequest>* stream) override;
  grpc::Status GetServerInfo(grpc::ServerContext* context, const v1::GetServerInfoRequest* request,
                             v1::GetServerInfoResponse* response) override;
  grpc::Status PlanRegions(grpc::ServerContext* context, const v1::PlanRegionsRequest* request,
                           v1::PlanRegionsResponse* response) override;

 private:
  // Validation, the request's scene update (on `live`, from the stored scene `stored` a stream's
  // check found, or found now when null), admission, rendering on the shared arena (stopped at
  // `stop_at` too; the update as well); fills the response's timings and returns what encodes the
  // frame into it.
  absl::StatusOr<EncodeFrameFn> RenderImage(grpc::ServerContext* context,
                                            const v1::RenderFrameRequest& request, LiveScene& live,
                                            std::shared_ptr<const Scene> stored,
                                            LiveClock::time_point stop_at,
                                            v1::RenderFrameResponse* response);
  // RenderImage, then the encode; fills `response`.
  absl::Status RenderOne(grpc::ServerContext* context, const v1::RenderFrameRequest& request,
                         v1::RenderFrameResponse* response);

  // The calls' own work, each filling its response and the fields of its log line.
  absl::Status Upload(grpc::ServerContext* context,
                      grpc::ServerReader<v1::UploadTextureRequest>* reader,
                      v1::UploadTextureResponse* response, std::string& sha256, bool& skipped);
  absl::Status Load(grpc::ServerContext* context, const v1::LoadSceneRequest& request,
                    v1::LoadSceneResponse* response, RpcCall& call);
  absl::Status Stream(
      grpc::ServerContext* context,
      grpc::ServerReaderWriter<v1::RenderFrameResponse, v1::RenderFrameRequest>* stream,
      RpcCall& call);
  void ServerInfo(v1::GetServerInfoResponse* response) const;

  const ServiceLimits limits_;
  TextureStore& textures_;
  SceneStore& scenes_;
  AdmissionControl& admission_;
  tbb::task_arena& arena_;
  const std::chrono::steady_clock::time_point started_ = std::chrono::steady_clock::now();
  std::atomic<uint64_t> frames_rendered_{0}, frames_failed_{0}, frames_skipped_{0};
  // Raytraced scenes' BVH and tables (about 100 MB per 1024² raster texture): the last few.
  static constexpr size_t kTracedScenes = 4;
  TracedSceneCache traced_;
  ByteBudget uploads_in_flight_;
  IdleWatchdog upload_watchdog_;
  RpcCalls calls_;
};

}  // namespace aperture
