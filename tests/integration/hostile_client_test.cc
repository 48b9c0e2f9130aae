// What a hostile or careless client may make the server do: scene loads bounded by
// their deadline and by the limits on polygons, vertices and textures; self-intersecting
// polygons refused. Real servers on loopback, real gRPC calls.
#include <gmock/gmock.h>
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <future>
#include <string>
#include <thread>

#include "content_hash.h"
#include "integration/service_fixture.h"
#include "support/hostile_inputs.h"

namespace aperture::testing {
namespace {

using ::testing::HasSubstr;
using Clock = std::chrono::steady_clock;

class HostileClientTest : public ServiceTest {
 protected:
  grpc::Status Load(const v1::Scene& scene, double seconds, v1::LoadSceneResponse* response) {
    grpc::ClientContext context;
    context.set_deadline(std::chrono::system_clock::now() +
                         std::chrono::microseconds(static_cast<int64_t>(seconds * 1e6)));
    v1::LoadSceneRequest request;
    *request.mutable_scene() = scene;
    return stub_->LoadScene(&context, request, response);
  }
  void CheckStoreBudget(const std::vector<std::string>& pngs);
};

// One ground polygon of `n` vertices, a star (concave) in the x-z plane.
void AddStar(v1::Scene& scene, int n, const std::string& material) {
  v1::Mesh& mesh = *scene.add_meshes();
  mesh.set_id("star");
  mesh.set_material_id(material);
  v1::Polygon& poly = *mesh.add_polygons();
  for (int i = 0; i < n; ++i) {
    const double a = -2 * M_PI * (i + 0.5) / n, r = i % 2 == 0 ? 100 : 60 + (i % 7);
    v1::Vec3& v = *poly.add_vertices();
    v.set_x(r * std::cos(a));
    v.set_z(r * std::sin(a));
  }
}

TEST_F(HostileClientTest, ASceneLoadStopsAtItsDeadlineAndFreesTheServer) {
  StartServer({"--max-message-mb=64"});
  // 200,000 vertices on a 2048 x 2048 texture filtered aniso: seed 000's table alone takes
  // several seconds to build.
  v1::Scene scene;
  scene.set_name("slow to load");
  v1::Texture& texture = *scene.add_textures();
  texture.set_id("checks");
  texture.mutable_checkerboard()->set_size(2048);
  v1::Material& material = *scene.add_materials();
  material.set_id("ground");
  material.set_texture_id("checks");
  material.set_filter(v1::TEXTURE_FILTER_ANISO);
  AddStar(scene, 200000, "ground");

  const auto start = Clock::now();
  v1::LoadSceneResponse response;
  const grpc::Status status = Load(scene, 1.0, &response);
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  EXPECT_EQ(status.error_code(), grpc::StatusCode::DEADLINE_EXCEEDED) << status.error_message();
  EXPECT_LT(seconds, 1.5);

  // The server stopped building: a frame right after is answered at once, and the log says
  // the load ended (not merely the client).
  const auto after = Clock::now();
  const std::string id = LoadBuiltinScene(*stub_, "triangles").scene_id();
  EXPECT_TRUE(Render(FrameRequest(id, 64, 48), 5).ok());
  EXPECT_LT(std::chrono::duration<double>(Clock::now() - after).count(), 2.0);
  for (int i = 0; i < 300 && server_->Log().find("status=DEADLINE_EXCEEDED") == std::string::npos;
       ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  // The server's own figure: how long the load ran before it stopped.
  const std::string log = server_->Log();
  const size_t line = log.find("name='slow to load'");
  ASSERT_NE(line, std::string::npos) << log;
  const size_t ms = log.find("ms=", line);
  ASSERT_NE(ms, std::string::npos) << log;
  EXPECT_LT(std::stod(log.substr(ms + 3)), 1500) << log.substr(line, 200);
  EXPECT_THAT(log.substr(line, 200), HasSubstr("status=DEADLINE_EXCEEDED"));
}

TEST_F(HostileClientTest, LimitsOnPolygonsVerticesAndTexturesNameTheLimit) {
  StartServer({"--max-scene-polygons=100", "--max-polygon-vertices=50", "--max-scene-textures=2"});
  v1::LoadSceneResponse response;

  v1::Scene many_vertices;
  AddStar(many_vertices, 60, "");
  grpc::Status status = Load(many_vertices, 10, &response);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(status.error_message(), HasSubstr("60 vertices, above the limit of 50"));

  v1::Scene many_objects;
  AddStar(many_objects, 40, "");
  for (int i = 0; i < 101; ++i) many_objects.add_objects()->set_mesh_id("star");
  status = Load(many_objects, 10, &response);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(status.error_message(), HasSubstr("101 polygons, above the limit of 100"));

  v1::Scene many_textures;
  for (int i = 0; i < 3; ++i) {
    v1::Texture& t = *many_textures.add_textures();
    t.set_id(std::string(1, static_cast<char>('a' + i)));
    t.mutable_checkerboard()->set_size(8);
  }
  status = Load(many_textures, 10, &response);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(status.error_message(), HasSubstr("above the limit of 2 textures per scene"));

  // Within every limit, the same server loads it.
  v1::Scene fits;
  AddStar(fits, 50, "");
  EXPECT_TRUE(Load(fits, 10, &response).ok());
}

TEST_F(HostileClientTest, APentagramIsRefusedNamingThePolygon) {
  StartServer();
  v1::Scene scene;
  v1::Mesh& mesh = *scene.add_meshes();
  mesh.set_id("star");
  v1::Polygon& poly = *mesh.add_polygons();
  for (int k = 0; k < 5; ++k) {
    const double a = 2 * M_PI * (2 * k) / 5;
    v1::Vec3& v = *poly.add_vertices();
    v.set_x(std::cos(a));
    v.set_z(std::sin(a));
  }
  v1::LoadSceneResponse response;
  const grpc::Status status = Load(scene, 10, &response);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(status.error_message(), HasSubstr("meshes[0].polygons[0]"));
  EXPECT_THAT(status.error_message(), HasSubstr("self-intersecting"));
}

// An upload stream: the first message announces `total` bytes and carries `chunk`.
struct OpenUpload {
  grpc::ClientContext context;
  v1::UploadTextureResponse response;
  std::unique_ptr<grpc::ClientWriter<v1::UploadTextureRequest>> writer;
};

std::unique_ptr<OpenUpload> StartUpload(v1::Render::Stub& stub, const std::string& sha256,
                                        uint64_t total, const std::string& chunk) {
  auto upload = std::make_unique<OpenUpload>();
  upload->context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(30));
  upload->writer = stub.UploadTexture(&upload->context, &upload->response);
  v1::UploadTextureRequest message;
  message.set_sha256(sha256);
  message.set_total_size(total);
  message.set_chunk(chunk);
  upload->writer->Write(message);
  return upload;
}

// In chunks of 1 MiB, the most one message may carry.
grpc::Status UploadWhole(v1::Render::Stub& stub, const std::string& bytes) {
  constexpr size_t kChunk = 1 << 20;
  auto upload = StartUpload(stub, Sha256Hex(bytes), bytes.size(), bytes.substr(0, kChunk));
  for (size_t offset = kChunk; offset < bytes.size(); offset += kChunk) {
    v1::UploadTextureRequest message;
    message.set_chunk(bytes.substr(offset, kChunk));
    if (!upload->writer->Write(message)) break;
  }
  upload->writer->WritesDone();
  return upload->writer->Finish();
}

TEST_F(HostileClientTest, UploadsThatAreNoTextureAreRefusedAndNotKept) {
  StartServer();
  const std::string passwd = "root:x:0:0:root:/root:/bin/bash\n";
  grpc::Status status = UploadWhole(*stub_, passwd);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(status.error_message(), HasSubstr("not a texture"));

  // A PNG declaring 16384 x 16384 texels is refused from its header alone.
  const std::string bomb = PngDeclaring(16384, 16384);
  ASSERT_LT(bomb.size(), 100u);
  status = UploadWhole(*stub_, bomb);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(status.error_message(), HasSubstr("16384x16384, above the limit"));

  for (const std::string& refused : {passwd, bomb}) {
    grpc::ClientContext context;
    v1::HasTextureRequest request;
    request.set_sha256(Sha256Hex(refused));
    v1::HasTextureResponse response;
    ASSERT_TRUE(stub_->HasTexture(&context, request, &response).ok());
    EXPECT_FALSE(response.stored());
  }
  EXPECT_TRUE(UploadWhole(*stub_, NoisePng(32, 32, 5)).ok());
}

TEST_F(HostileClientTest, AStalledUploadIsCancelledAndItsBytesFreed) {
  StartServer({"--upload-idle-s=1.5", "--max-upload-inflight-mb=12"});
  const std::string png = NoisePng(64, 64, 6);
  // Announces 10 MiB, sends a few bytes, then nothing.
  const auto start = Clock::now();
  auto stalled = StartUpload(*stub_, Sha256Hex("stalled"), 10 << 20, png.substr(0, 100));
  for (int i = 0; i < 100 && Info().budgets().upload_bytes_in_flight() == 0; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_EQ(Info().budgets().upload_bytes_in_flight(), 10u << 20);

  // Meanwhile the budget holds the announced bytes: a second 10 MiB upload does not fit.
  auto second = StartUpload(*stub_, Sha256Hex("second"), 10 << 20, png.substr(0, 100));
  grpc::Status status = second->writer->Finish();
  EXPECT_EQ(status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_THAT(status.error_message(), HasSubstr("uploads in flight (--max-upload-inflight-mb)"));

  status = stalled->writer->Finish();  // returns when the server cancels the stream
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  EXPECT_FALSE(status.ok());
  EXPECT_LT(seconds, 5.0);
  EXPECT_GT(seconds, 1.4);
  // The client sees the cancellation as soon as the server calls TryCancel; the handler frees the
  // reservation when its read loop unwinds, a moment later on a loaded machine.
  for (int i = 0; i < 200 && Info().budgets().upload_bytes_in_flight() != 0; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_EQ(Info().budgets().upload_bytes_in_flight(), 0u);

  // Its reservation is back: 10 MiB announced again get past the budget (and, being no texture,
  // are then refused for that).
  const std::string junk(10 << 20, 'j');
  status = UploadWhole(*stub_, junk);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << status.error_message();
  for (int i = 0; i < 100 && server_->Log().find("upload idle") == std::string::npos; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_THAT(server_->Log(), HasSubstr("upload idle for 1.5 s after 100 of 10485760 bytes"));
}

bool Stored(v1::Render::Stub& stub, const std::string& bytes) {
  grpc::ClientContext context;
  v1::HasTextureRequest request;
  request.set_sha256(Sha256Hex(bytes));
  v1::HasTextureResponse response;
  EXPECT_TRUE(stub.HasTexture(&context, request, &response).ok());
  return response.stored();
}

grpc::Status LoadRequest(v1::Render::Stub& stub, const v1::LoadSceneRequest& request,
                         v1::LoadSceneResponse* response) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(30));
  return stub.LoadScene(&context, request, response);
}

TEST_F(HostileClientTest, APngThatDeclaresAHugeImageIsWeighedBeforeItIsDecoded) {
  StartServer({"--max-scenes-mb=512"});
  // 8192 x 8192 is within the texel limit, so the upload is kept; decoded it would be 1.3 GiB.
  const std::string bomb = PngDeclaring(8192, 8192);
  ASSERT_TRUE(UploadWhole(*stub_, bomb).ok());
  v1::LoadSceneResponse response;
  const grpc::Status status = LoadRequest(*stub_, TexturedGroundScene(Sha256Hex(bomb)), &response);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_THAT(status.error_message(), HasSubstr("1365.3 MiB"));
  EXPECT_THAT(status.error_message(), HasSubstr("loaded scenes (--max-scenes-mb), 512 MiB"));
  EXPECT_EQ(Info().budgets().scene_bytes(), 0u);
}

TEST_F(HostileClientTest, ScenesPastTheirBudgetEvictTheLeastRecentlyUsed) {
  // Checkerboards of 1024 x 1024 texels: 21.3 MiB each as a float mip-map. Two fit in 50 MiB.
  StartServer({"--max-scenes-mb=50"});
  std::vector<std::string> ids;
  for (uint32_t size : {1024u, 1023u, 1022u}) {  // three different scenes of the same weight
    v1::LoadSceneResponse response;
    ASSERT_TRUE(LoadRequest(*stub_, TexturedGroundScene("", size), &response).ok());
    ids.push_back(response.scene_id());
    const v1::Budgets budgets = Info().budgets();
    EXPECT_LE(budgets.scene_bytes(), budgets.scene_budget_bytes());
  }
  EXPECT_EQ(Info().budgets().scenes_evicted(), 1u);
  EXPECT_EQ(Render(FrameRequest(ids[0], 16, 16), 10).error_code(), grpc::StatusCode::NOT_FOUND);
  EXPECT_TRUE(Render(FrameRequest(ids[1], 16, 16), 10).ok());
  EXPECT_TRUE(Render(FrameRequest(ids[2], 16, 16), 10).ok());
}

TEST_F(HostileClientTest, TheStoreStaysWithinItsBudgetAndScenesKeepTheirPixels) {
  std::vector<std::string> pngs;
  for (uint32_t seed = 10; seed < 13; ++seed) pngs.push_back(NoisePng(1024, 1024, seed));
  // The shared store on /dev/shm, and uploads held in memory.
  for (const std::string store : {"", "--store=none"}) {
    SCOPED_TRACE(store);
    own_server_.reset();
    // Noise PNGs of about 3.1 MB: two fit in 7 MiB, a third evicts the least recently used.
    StartServer(store.empty() ? std::vector<std::string>{"--max-store-mb=7"}
                              : std::vector<std::string>{"--max-store-mb=7", store});
    CheckStoreBudget(pngs);
  }
}

void HostileClientTest::CheckStoreBudget(const std::vector<std::string>& pngs) {
  ASSERT_TRUE(UploadWhole(*stub_, pngs[0]).ok());
  ASSERT_TRUE(UploadWhole(*stub_, pngs[1]).ok());
  v1::LoadSceneResponse scene;
  ASSERT_TRUE(LoadRequest(*stub_, TexturedGroundScene(Sha256Hex(pngs[0])), &scene).ok());
  ASSERT_TRUE(UploadWhole(*stub_, pngs[2]).ok());

  const v1::Budgets budgets = Info().budgets();
  EXPECT_LE(budgets.store_bytes(), budgets.store_budget_bytes());
  EXPECT_EQ(budgets.store_budget_bytes(), 7u << 20);
  EXPECT_EQ(budgets.store_entries_evicted(), 1u);
  // pngs[0] was used by the load after pngs[1] was uploaded: pngs[1] is the one evicted.
  EXPECT_TRUE(Stored(*stub_, pngs[0]));
  EXPECT_FALSE(Stored(*stub_, pngs[1]));
  EXPECT_TRUE(Stored(*stub_, pngs[2]));
  // The loaded scene holds its decoded texture: it renders whatever the store evicts.
  ASSERT_TRUE(UploadWhole(*stub_, pngs[1]).ok());
  EXPECT_FALSE(Stored(*stub_, pngs[0]));
  v1::RenderFrameResponse frame;
  EXPECT_TRUE(Render(FrameRequest(scene.scene_id(), 32, 32), 10, &frame).ok());
  EXPECT_FALSE(Pixels(frame).empty());
}

// A frame whose deadline passes while it waits for a turn leaves the queue at
// once and is answered DEADLINE_EXCEEDED (in the server's log too, not CANCELLED).
TEST_F(HostileClientTest, ADeadlineThatPassesInTheQueueFreesTheSlotAtOnce) {
  StartServer({"--concurrent-frames=1", "--max-queue=1"});
  const v1::RenderFrameRequest slow = SlowFrame();
  auto busy = std::async(std::launch::async, [&] { return Render(slow, 20); });
  for (int i = 0; i < 500 && Info().frames_in_flight() == 0; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ASSERT_EQ(Info().frames_in_flight(), 1u);

  const std::string id = LoadBuiltinScene(*stub_, "triangles").scene_id();
  const auto start = Clock::now();
  const grpc::Status waited = Render(FrameRequest(id, 16, 16), 0.3);
  EXPECT_EQ(waited.error_code(), grpc::StatusCode::DEADLINE_EXCEEDED);
  // The slot is free again at once: the queue (of one) takes the next frame.
  for (int i = 0; i < 20 && Info().frames_queued() > 0; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_EQ(Info().frames_queued(), 0u);
  EXPECT_LT(std::chrono::duration<double>(Clock::now() - start).count(), 0.6);
  for (int i = 0; i < 100 && server_->Log().find("passed in the queue") == std::string::npos; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_THAT(server_->Log(), HasSubstr("status=DEADLINE_EXCEEDED error='the call\\'s deadline "
                                        "passed in the queue'"));
  own_server_.reset();  // the slow frame ends with its server
  (void)busy.get();
}

// A client that retries a refused frame at once: the server's log gets about a line a second for
// the refusals, each with its count (which add up to every refusal), not a line per refusal.
TEST_F(HostileClientTest, AFloodOfRefusedFramesKeepsTheLogShort) {
  StartServer({"--concurrent-frames=1", "--max-queue=0"});
  const v1::RenderFrameRequest slow = SlowFrame();
  auto busy = std::async(std::launch::async, [&] { return Render(slow, 30); });
  for (int i = 0; i < 500 && Info().frames_in_flight() == 0; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ASSERT_EQ(Info().frames_in_flight(), 1u);

  const std::string id = LoadBuiltinScene(*stub_, "triangles").scene_id();
  const auto lines = [&] {
    const std::string log = server_->Log();
    return std::count(log.begin(), log.end(), '\n');
  };
  const auto lines_before = lines();
  constexpr int kRefused = 2000;
  const auto start = Clock::now();
  for (int i = 0; i < kRefused; ++i)
    ASSERT_EQ(Render(FrameRequest(id, 16, 16), 10).error_code(),
              grpc::StatusCode::RESOURCE_EXHAUSTED);
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  // Every refusal is counted in some line: the burst's tail is written by the flushing thread
  // within 1.25 s of the last line before it (waited for up to 5 s on a loaded machine).
  const auto counted_in = [](const std::string& log) {
    int counted = 0;
    for (size_t at = log.find("refused "); at != std::string::npos;
         at = log.find("refused ", at + 1))
      counted += std::atoi(log.c_str() + at + 8);
    return counted;
  };
  for (int i = 0; i < 500 && counted_in(server_->Log()) < kRefused; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  const std::string log = server_->Log();
  EXPECT_EQ(counted_in(log), kRefused);
  const auto written = lines() - lines_before;
  EXPECT_LE(written, 3 + static_cast<long>(seconds)) << "over " << seconds << " s";
  EXPECT_THAT(log, HasSubstr("frames in the last "));
  EXPECT_THAT(log, HasSubstr(": queue full; the latest: req="));
  EXPECT_EQ(Info().frames_rejected(), static_cast<uint64_t>(kRefused));
  own_server_.reset();  // the slow frame ends with its server
  (void)busy.get();
}

}  // namespace
}  // namespace aperture::testing
