// aperture-server: the render service over gRPC. One oneTBB arena shared by all requests, a
// bounded admission queue, health service and reflection, graceful shutdown on SIGTERM/SIGINT.
#include <grpcpp/ext/proto_server_reflection_plugin.h>
#include <grpcpp/grpcpp.h>
#include <grpcpp/health_check_service_interface.h>
#include <malloc.h>
#include <signal.h>
#include <spdlog/cfg/env.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <sys/statvfs.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/task_arena.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <thread>

#include "absl/flags/flag.h"
#include "absl/flags/parse.h"
#include "absl/flags/usage.h"
#include "admission.h"
#include "auth_tokens.h"
#include "cli_usage.h"
#include "cost/window_cost.h"
#include "flag_names.h"
#include "keepalive.h"
#include "large_buffers.h"
#include "metrics_http.h"
#include "metrics_interceptor.h"
#include "render/frame_memory.h"
#include "render_service.h"
#include "scene_store.h"
#include "store/shared_store.h"
#include "texture_store.h"

ABSL_FLAG(std::string, listen, "127.0.0.1:50051",
          "address to listen on, HOST:PORT (port 0: any free port, printed at start)");
ABSL_FLAG(int, threads, 0, "render worker threads in the shared oneTBB arena (0: all cores)");
ABSL_FLAG(int, concurrent_frames, 2, "frames rendered at once (they share the arena's threads)");
ABSL_FLAG(int, max_queue, 16, "frames waiting for a turn; past it RESOURCE_EXHAUSTED at once");
ABSL_FLAG(uint64_t, max_pixels, 4096ull * 4096, "largest frame, width x height");
ABSL_FLAG(int, max_message_mb, 64, "largest request message (scenes, chunks), MiB");
ABSL_FLAG(int, max_texture_mb, 256, "largest uploaded texture, MiB");
ABSL_FLAG(int, max_upload_inflight_mb, 1024,
          "announced bytes of all uploads streaming at once, MiB; past it RESOURCE_EXHAUSTED");
ABSL_FLAG(double, upload_idle_s, 30,
          "an upload stream that sends nothing for this long is cancelled and its bytes freed");
ABSL_FLAG(uint64_t, max_scene_polygons, 4000000,
          "largest scene: its objects times their meshes' polygons (before triangulation)");
ABSL_FLAG(uint64_t, max_polygon_vertices, 1000000, "most vertices of one polygon");
ABSL_FLAG(uint64_t, max_scene_textures, 256, "most textures of one scene");
ABSL_FLAG(uint64_t, max_scene_lights, 1000000, "most light points of one scene, rows expanded");
ABSL_FLAG(uint64_t, max_scenes_mb, 0,
          "bytes all loaded scenes may hold (decoded textures, aniso tables, polygons, as "
          "estimated before a scene is built), MiB; 0: a quarter of the machine's memory");
ABSL_FLAG(uint64_t, max_store_mb, 0,
          "bytes the texture store may hold (uploads, tables, packed textures; with --store none "
          "the uploads in memory), MiB; past it the least recently used entries are evicted; 0: "
          "half the store's file system (an eighth of the machine's memory with --store none)");
ABSL_FLAG(int, max_scenes, 64, "scenes kept loaded; past it the least recently used is dropped");
ABSL_FLAG(uint64_t, max_frame_mb, 0,
          "working memory one frame may hold (projected polygons, planned tasks, the workers' "
          "cell buffers, the image), MiB; past it the frame stops with RESOURCE_EXHAUSTED; 0: a "
          "quarter of the machine's memory");
ABSL_FLAG(std::string, store, aperture::kDefaultStoreDirectory,
          "shared texture store: a directory (under /dev/shm: POSIX shared memory) holding "
          "uploads, seed 000 tables and packed textures, mapped by every server on the machine "
          "and kept across restarts; 'none': memory only, nothing shared");
ABSL_FLAG(std::string, tls_cert, "",
          "PEM certificate chain; with --tls-key the server accepts only TLS connections");
ABSL_FLAG(std::string, tls_key, "", "PEM private key of --tls-cert");
ABSL_FLAG(std::string, tls_client_ca, "",
          "PEM CA certificates: with --tls-cert/--tls-key, clients must present a certificate "
          "signed by one of them (mutual TLS)");
ABSL_FLAG(std::string, auth_tokens, "",
          "file of accepted bearer tokens, one per line ('#' comments), read again on SIGHUP: "
          "every RPC but health then needs 'authorization: Bearer <token>' metadata");
ABSL_FLAG(bool, insecure_listen_any, false,
          "allow --listen on an address other machines reach without --auth-tokens or "
          "--tls-client-ca (anyone who connects may upload, load and render)");
ABSL_FLAG(std::string, metrics_listen, "",
          "serve Prometheus metrics over HTTP at HOST:PORT, path /metrics (port 0: any free "
          "port, logged at start); empty: off. Read-only counters without authentication: give "
          "an address only the monitoring system reaches");
ABSL_FLAG(double, grace_s, 10,
          "on SIGTERM: seconds in-flight frames get to finish before they "
          "are cancelled");

ABSL_FLAG(std::string, cost_model, "",
          "the tile cost model (aperture-render --calibrate writes one); a missing or malformed "
          "file stops the start (default: $APERTURE_COST_MODEL, else share/aperture/"
          "cost_model.txt of this installation, else built-in constants)");

namespace aperture {
namespace {

// TLS when both --tls-cert and --tls-key are given (requiring client certificates signed by
// --tls-client-ca when that is given), plaintext when neither; null (after logging why) when only
// one is, or a file cannot be read.
std::shared_ptr<grpc::ServerCredentials> ServerCredentials() {
  const std::string cert = absl::GetFlag(FLAGS_tls_cert), key = absl::GetFlag(FLAGS_tls_key);
  const std::string client_ca = absl::GetFlag(FLAGS_tls_client_ca);
  if (cert.empty() && key.empty()) {
    if (!client_ca.empty()) {
      spdlog::error("--tls-client-ca needs --tls-cert and --tls-key (mutual TLS is TLS)");
      return nullptr;
    }
    return grpc::InsecureServerCredentials();
  }
  if (cert.empty() || key.empty()) {
    spdlog::error("--tls-cert and --tls-key go together; give both or neither");
    return nullptr;
  }
  auto read = [](const std::string& path) {
    std::ifstream in(path);
    std::ostringstream content;
    content << in.rdbuf();
    return content.str();
  };
  grpc::SslServerCredentialsOptions options;
  options.pem_key_cert_pairs.push_back({read(key), read(cert)});
  if (options.pem_key_cert_pairs[0].private_key.empty() ||
      options.pem_key_cert_pairs[0].cert_chain.empty()) {
    spdlog::error("cannot read --tls-key {} or --tls-cert {}", key, cert);
    return nullptr;
  }
  if (!client_ca.empty()) {
    options.pem_root_certs = read(client_ca);
    if (options.pem_root_certs.empty()) {
      spdlog::error("cannot read --tls-client-ca {}", client_ca);
      return nullptr;
    }
    options.client_certificate_request = GRPC_SSL_REQUEST_AND_REQUIRE_CLIENT_CERTIFICATE_AND_VERIFY;
  }
  return grpc::SslServerCredentials(options);
}

// Loopback addresses only this machine reaches: without authentication the server listens on
// nothing else unless --insecure-listen-any says so.
bool IsLoopbackHost(std::string host) {
  if (host.size() >= 2 && host.front() == '[' && host.back() == ']')
    host = host.substr(1, host.size() - 2);
  return host == "localhost" || host == "::1" || host.rfind("127.", 0) == 0;
}

int Run() {
  // Signals are taken by one thread with sigwait; block them before gRPC and oneTBB start theirs.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGTERM);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGHUP);  // reloads --auth-tokens
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);

  ServiceLimits limits;
  limits.threads = absl::GetFlag(FLAGS_threads) > 0 ? absl::GetFlag(FLAGS_threads)
                                                    : tbb::info::default_concurrency();
  limits.concurrent_frames = std::max(1, absl::GetFlag(FLAGS_concurrent_frames));
  limits.max_queue = std::max(0, absl::GetFlag(FLAGS_max_queue));
  limits.max_pixels = absl::GetFlag(FLAGS_max_pixels);
  limits.max_message_bytes = uint64_t(std::max(1, absl::GetFlag(FLAGS_max_message_mb))) << 20;
  limits.max_texture_bytes = uint64_t(std::max(1, absl::GetFlag(FLAGS_max_texture_mb))) << 20;
  limits.max_upload_inflight_bytes =
      uint64_t(std::max(1, absl::GetFlag(FLAGS_max_upload_inflight_mb))) << 20;
  limits.upload_idle = std::chrono::milliseconds(
      static_cast<int64_t>(std::max(0.05, absl::GetFlag(FLAGS_upload_idle_s)) * 1000));
  limits.scene.polygons = absl::GetFlag(FLAGS_max_scene_polygons);
  limits.scene.vertices_per_polygon = absl::GetFlag(FLAGS_max_polygon_vertices);
  limits.scene.textures = absl::GetFlag(FLAGS_max_scene_textures);
  limits.scene.lights = absl::GetFlag(FLAGS_max_scene_lights);
  limits.max_frame_bytes = absl::GetFlag(FLAGS_max_frame_mb) > 0
                               ? absl::GetFlag(FLAGS_max_frame_mb) << 20
                               : DefaultFrameBudgetBytes();

  if (const std::string path = absl::GetFlag(FLAGS_cost_model); !path.empty()) {
    if (auto s = UseCostModelFile(path); !s.ok()) {
      spdlog::error("--cost-model: {}", std::string(s.message()));
      return 2;
    }
  }

  tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism,
                                  static_cast<size_t>(limits.threads));
  // One arena for all requests: a slot reserved for each frame's request thread (so a frame
  // never waits for another's slot), workers capped at threads - 1 by the global control.
  tbb::task_arena arena(limits.threads + limits.concurrent_frames - 1,
                        static_cast<unsigned>(limits.concurrent_frames));
  std::shared_ptr<const SharedStore> shared_store;
  if (const std::string directory = absl::GetFlag(FLAGS_store); directory != "none") {
    auto opened = SharedStore::Open(directory);
    if (!opened.ok()) {
      spdlog::error("--store {}: {}", directory, opened.status().ToString());
      return 2;
    }
    shared_store = *std::move(opened);
  }
  std::unique_ptr<AuthTokens> auth;
  if (const std::string path = absl::GetFlag(FLAGS_auth_tokens); !path.empty()) {
    auto loaded = AuthTokens::Load(path);
    if (!loaded.ok()) {
      spdlog::error("{}", std::string(loaded.status().message()));
      return 2;
    }
    auth = *std::move(loaded);
  }
  const std::string listen = absl::GetFlag(FLAGS_listen);
  const std::string host = listen.substr(0, listen.rfind(':'));
  const bool mutual_tls = !absl::GetFlag(FLAGS_tls_client_ca).empty();
  if (!auth && !mutual_tls && !IsLoopbackHost(host) && !absl::GetFlag(FLAGS_insecure_listen_any)) {
    spdlog::error(
        "--listen {}: other machines reach this address, and no client would need to "
        "authenticate; give --auth-tokens FILE (or --tls-client-ca), or --insecure-listen-any "
        "on a network you trust",
        listen);
    return 2;
  }
  const uint64_t memory_bytes = static_cast<uint64_t>(sysconf(_SC_PHYS_PAGES)) *
                                static_cast<uint64_t>(sysconf(_SC_PAGE_SIZE));
  const uint64_t scenes_budget = absl::GetFlag(FLAGS_max_scenes_mb) > 0
                                     ? absl::GetFlag(FLAGS_max_scenes_mb) << 20
                                     : memory_bytes / 4;
  limits.max_store_bytes = absl::GetFlag(FLAGS_max_store_mb) << 20;
  if (limits.max_store_bytes == 0) {
    struct statvfs fs {};
    limits.max_store_bytes = shared_store && statvfs(shared_store->directory().c_str(), &fs) == 0
                                 ? static_cast<uint64_t>(fs.f_blocks) * fs.f_frsize / 2
                                 : memory_bytes / 8;
  }
  TextureStore textures(shared_store);
  textures.SetBudget(limits.max_store_bytes);
  // A store left over its budget (by a process with a larger one) is trimmed at start.
  if (const uint64_t evicted = textures.Trim(limits.max_store_bytes); evicted > 0)
    spdlog::info("texture store over --max-store-mb at start: {} entries evicted", evicted);
  SceneStore scenes(static_cast<size_t>(std::max(1, absl::GetFlag(FLAGS_max_scenes))),
                    scenes_budget);
  AdmissionControl admission(limits.concurrent_frames, limits.max_queue);
  RenderService service(limits, textures, scenes, admission, arena, auth.get());
  std::unique_ptr<ServiceMetrics> metrics;  // --metrics-listen: fed by an interceptor
  if (!absl::GetFlag(FLAGS_metrics_listen).empty()) {
    metrics = std::make_unique<ServiceMetrics>();
    metrics->Watch(admission, textures, scenes, limits.max_store_bytes);
  }

  const std::shared_ptr<grpc::ServerCredentials> credentials = ServerCredentials();
  if (!credentials) return 2;
  grpc::EnableDefaultHealthCheckService(true);
  grpc::reflection::InitProtoReflectionServerBuilderPlugin();
  grpc::ServerBuilder builder;
  int port = 0;
  builder.AddListeningPort(listen, credentials, &port);
  builder.SetMaxReceiveMessageSize(static_cast<int>(limits.max_message_bytes));
  builder.SetMaxSendMessageSize(-1);  // frames: 3840x2160 float RGBA is ~130 MB uncompressed
  builder.AddChannelArgument(GRPC_ARG_KEEPALIVE_TIME_MS, keepalive::kTimeMs);
  builder.AddChannelArgument(GRPC_ARG_KEEPALIVE_TIMEOUT_MS, keepalive::kTimeoutMs);
  builder.AddChannelArgument(GRPC_ARG_HTTP2_MIN_RECV_PING_INTERVAL_WITHOUT_DATA_MS,
                             keepalive::kServerMinPingIntervalMs);
  builder.RegisterService(&service);
  if (metrics) {
    std::vector<std::unique_ptr<grpc::experimental::ServerInterceptorFactoryInterface>> creators;
    creators.push_back(MetricsInterceptorFactory(*metrics));
    builder.experimental().SetInterceptorCreators(std::move(creators));
  }
  std::unique_ptr<grpc::Server> server = builder.BuildAndStart();
  if (!server || port == 0) {
    spdlog::error("cannot listen on {}", listen);
    return 2;
  }
  std::unique_ptr<MetricsHttpServer> metrics_http;
  if (metrics) {
    auto started = MetricsHttpServer::Start(absl::GetFlag(FLAGS_metrics_listen), *metrics);
    if (!started.ok()) {
      spdlog::error("{}", std::string(started.status().message()));
      return 2;
    }
    metrics_http = *std::move(started);
    spdlog::info("metrics on http://{}{}", metrics_http->address(), MetricsHttpServer::kPath);
  }
  // The first line on stdout is for scripts and tests that asked for port 0.
  std::printf("listening on %s:%d\n", host.c_str(), port);
  std::fflush(stdout);
  spdlog::info(
      "aperture-server listening on {}:{} threads={} concurrent_frames={} max_queue={} "
      "max_pixels={} store='{}' store_budget_mb={} scenes_budget_mb={} frame_budget_mb={} "
      "cost_model='{}' tls={} auth={}",
      host, port, limits.threads, limits.concurrent_frames, limits.max_queue, limits.max_pixels,
      absl::GetFlag(FLAGS_store), limits.max_store_bytes >> 20, scenes.budget() >> 20,
      limits.max_frame_bytes >> 20, DefaultCostModelSource(),
      absl::GetFlag(FLAGS_tls_cert).empty() ? "off" : (mutual_tls ? "mutual" : "on"),
      auth                   ? "bearer tokens (" + auth->path() + ")"
      : mutual_tls           ? "client certificates"
      : IsLoopbackHost(host) ? "none (loopback only)"
                             : "NONE (--insecure-listen-any: anyone who connects is served)");
  server->GetHealthCheckService()->SetServingStatus(true);

  std::thread signal_waiter([&] {
    int signal = 0;
    while (sigwait(&signals, &signal) == 0 && signal == SIGHUP) {
      if (!auth) {
        spdlog::info("SIGHUP: no --auth-tokens to reload");
        continue;
      }
      auto reloaded = auth->Reload();
      if (reloaded.ok())
        spdlog::info("SIGHUP: {} tokens accepted from {}", *reloaded, auth->path());
      else
        spdlog::error("SIGHUP: {}; the tokens accepted before stay",
                      std::string(reloaded.status().message()));
    }
    const double grace = absl::GetFlag(FLAGS_grace_s);
    spdlog::info("signal {}: shutting down; {} frames rendering, {} queued, grace {} s", signal,
                 admission.running(), admission.queued(), grace);
    server->GetHealthCheckService()->SetServingStatus(false);
    // A frame stuck where no stop test reaches it (inside a library) must not keep the process
    // alive for ever: past the grace period and a margin, exit so the supervisor restarts it.
    std::thread([grace] {
      std::this_thread::sleep_for(std::chrono::milliseconds(static_cast<int64_t>(grace * 1000)) +
                                  std::chrono::seconds(5));
      spdlog::error("shutdown still waiting for a request {} s after the grace period; exiting", 5);
      spdlog::default_logger()->flush();
      std::_Exit(1);
    }).detach();
    // New calls are refused; calls still running at the deadline are cancelled, which stops
    // their frames between tasks.
    server->Shutdown(std::chrono::system_clock::now() +
                     std::chrono::milliseconds(static_cast<int64_t>(grace * 1000)));
  });
  server->Wait();
  signal_waiter.join();
  spdlog::info("aperture-server stopped");
  return 0;
}

}  // namespace
}  // namespace aperture

int main(int argc, char** argv) {
  aperture::KeepLargeBuffersWarm();  // frames' buffers reused warm, not page-faulted afresh
  aperture::HandleHelpAndVersion(
      argc, argv, "aperture-server",
      "serves aperture.v1.Render over gRPC.\n  aperture-server --listen 127.0.0.1:50051 "
      "--threads 0 --max-queue 16 --max-pixels 16777216 --store DIR");
  aperture::DashedFlagNames args(argc, argv);
  absl::ParseCommandLine(args.argc(), args.argv());
  // glibc gives every thread that allocates its own heap arena (up to 8 per core) and keeps freed
  // frame buffers in each, so a long load run grew RSS by 20 % in 5 minutes (gRPC runs requests
  // on a changing set of threads). A few arenas keep it flat at the same throughput
  // (docs/BENCHMARKS.md).
  mallopt(M_ARENA_MAX, std::max(2, absl::GetFlag(FLAGS_threads)));
  // Logs go to stderr; stdout carries only the "listening on" line.
  spdlog::set_default_logger(spdlog::stderr_color_mt("aperture-server"));
  spdlog::cfg::load_env_levels();  // SPDLOG_LEVEL=warn quiets the per-request lines
  return aperture::Run();
}
