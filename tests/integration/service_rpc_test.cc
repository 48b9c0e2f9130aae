// Every RPC of aperture.v1.Render against a real server process, and its error answers.
#include <gmock/gmock.h>
#include <grpcpp/generic/generic_stub.h>
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <thread>
#include <utility>

#include "content_hash.h"
#include "frame/camera_proto.h"
#include "grpc/health/v1/health.grpc.pb.h"
#include "integration/service_fixture.h"
#include "scene/demo_scene.h"
#include "scene/scene_builder.h"

namespace aperture::testing {
namespace {

using ::testing::HasSubstr;

grpc::Status Upload(v1::Render::Stub& stub, const std::string& sha256, const std::string& bytes,
                    size_t chunk_size, v1::UploadTextureResponse* response) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(20));
  auto writer = stub.UploadTexture(&context, response);
  for (size_t offset = 0; offset < bytes.size(); offset += chunk_size) {
    v1::UploadTextureRequest message;
    if (offset == 0) {
      message.set_sha256(sha256);
      message.set_total_size(bytes.size());
    }
    message.set_chunk(bytes.substr(offset, chunk_size));
    if (!writer->Write(message)) break;
  }
  writer->WritesDone();
  return writer->Finish();
}

bool HasTexture(v1::Render::Stub& stub, const std::string& sha256) {
  grpc::ClientContext context;
  v1::HasTextureRequest request;
  request.set_sha256(sha256);
  v1::HasTextureResponse response;
  EXPECT_TRUE(stub.HasTexture(&context, request, &response).ok());
  return response.stored();
}

TEST_F(ServiceTest, HealthServiceReportsServing) {
  StartServer();
  auto health = grpc::health::v1::Health::NewStub(
      grpc::CreateChannel(server_->address(), grpc::InsecureChannelCredentials()));
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(5));
  grpc::health::v1::HealthCheckResponse response;
  ASSERT_TRUE(health->Check(&context, {}, &response).ok());
  EXPECT_EQ(response.status(), grpc::health::v1::HealthCheckResponse::SERVING);
}

// Asks the reflection service for its list of services, with a generic call (Debian ships no
// reflection stubs): the request is ServerReflectionRequest{list_services: ""}.
TEST_F(ServiceTest, ReflectionListsTheRenderService) {
  StartServer();
  grpc::GenericStub stub(
      grpc::CreateChannel(server_->address(), grpc::InsecureChannelCredentials()));
  grpc::CompletionQueue queue;
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(10));
  auto call = stub.PrepareCall(
      &context, "/grpc.reflection.v1alpha.ServerReflection/ServerReflectionInfo", &queue);
  auto step = [&queue] {
    void* tag = nullptr;
    bool ok = false;
    return queue.Next(&tag, &ok) && ok;
  };
  call->StartCall(nullptr);
  ASSERT_TRUE(step());
  const char list_services[] = {0x3a, 0x00};  // field 7 (list_services), empty string
  grpc::Slice slice(list_services, sizeof list_services);
  grpc::ByteBuffer request(&slice, 1);
  call->Write(request, nullptr);
  ASSERT_TRUE(step());
  grpc::ByteBuffer response;
  call->Read(&response, nullptr);
  ASSERT_TRUE(step());
  std::vector<grpc::Slice> slices;
  ASSERT_TRUE(response.Dump(&slices).ok());
  std::string bytes;
  for (const grpc::Slice& s : slices)
    bytes.append(reinterpret_cast<const char*>(s.begin()), s.size());
  EXPECT_NE(bytes.find("aperture.v1.Render"), std::string::npos);
  EXPECT_NE(bytes.find("grpc.health.v1.Health"), std::string::npos);
  context.TryCancel();
  grpc::Status status;
  call->Finish(&status, nullptr);
  step();
  queue.Shutdown();
  void* tag = nullptr;
  bool ok = false;
  while (queue.Next(&tag, &ok)) {
  }
}

TEST_F(ServiceTest, UploadInChunksThenTheSecondUploadIsSkipped) {
  StartServer();
  const uint32_t textures_before = Info().textures();
  const std::string bytes = NoisePng(1024, 1024, 1);  // several 1 MiB chunks
  ASSERT_GT(bytes.size(), 3u << 20);
  const std::string sha256 = Sha256Hex(bytes);
  EXPECT_FALSE(HasTexture(*stub_, sha256));

  v1::UploadTextureResponse first;
  ASSERT_TRUE(Upload(*stub_, sha256, bytes, 1 << 20, &first).ok());
  EXPECT_FALSE(first.already_stored());
  EXPECT_EQ(first.size(), bytes.size());
  EXPECT_TRUE(HasTexture(*stub_, sha256));

  v1::UploadTextureResponse second;
  ASSERT_TRUE(Upload(*stub_, sha256, bytes, 1 << 20, &second).ok());
  EXPECT_TRUE(second.already_stored());
  EXPECT_EQ(Info().textures(), textures_before + 1);
}

TEST_F(ServiceTest, StoreDirectoryKeepsTexturesAcrossRestarts) {
  const std::string store = ::testing::TempDir() + "aperture_store_" + std::to_string(getpid());
  std::filesystem::create_directories(store);
  const std::string bytes = NoisePng(16, 16, 2);  // a texture kept across a restart
  StartServer({"--store=" + store});
  v1::UploadTextureResponse response;
  ASSERT_TRUE(Upload(*stub_, Sha256Hex(bytes), bytes, 1 << 20, &response).ok());
  own_server_.reset();  // SIGKILL

  StartServer({"--store=" + store});
  EXPECT_TRUE(HasTexture(*stub_, Sha256Hex(bytes)));
  ASSERT_TRUE(Upload(*stub_, Sha256Hex(bytes), bytes, 1 << 20, &response).ok());
  EXPECT_TRUE(response.already_stored());
  std::filesystem::remove_all(store);
}

TEST_F(ServiceTest, UploadErrorsNameTheField) {
  StartServer();
  v1::UploadTextureResponse response;
  grpc::Status status = Upload(*stub_, "not-a-hash", "abc", 1 << 20, &response);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(status.error_message(), HasSubstr("sha256"));

  status = Upload(*stub_, Sha256Hex("other content"), "abc", 1 << 20, &response);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(status.error_message(), HasSubstr("hashes to"));

  const std::string big(1536 << 10, 'x');  // 1.5 MiB in one chunk: under the message limit
  status = Upload(*stub_, Sha256Hex(big), big, big.size(), &response);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(status.error_message(), HasSubstr("chunk"));
}

TEST_F(ServiceTest, LoadSceneResolvesUploadedTexturesAndRefusesUnknownOnes) {
  StartServer();
  const std::string scene_id = LoadDemoScene();
  EXPECT_EQ(scene_id.size(), 64u);
  EXPECT_EQ(LoadDemoScene(), scene_id) << "the same scene loads to the same id";

  v1::LoadSceneRequest request;
  request.mutable_scene()->add_textures()->set_id("grass");
  (*request.mutable_texture_sha256())["grass"] = Sha256Hex("never uploaded");
  grpc::ClientContext context;
  v1::LoadSceneResponse response;
  grpc::Status status = stub_->LoadScene(&context, request, &response);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::NOT_FOUND);
  EXPECT_THAT(status.error_message(), HasSubstr("texture_sha256['grass']"));

  v1::LoadSceneRequest with_file;
  with_file.mutable_scene()->add_textures()->set_file("/etc/passwd");
  grpc::ClientContext context2;
  status = stub_->LoadScene(&context2, with_file, &response);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(status.error_message(), HasSubstr("scene.textures[0]"));
}

TEST_F(ServiceTest, BuiltinScenesAreBuiltByTheServerWithTheirCamera) {
  StartServer({"--max-scenes=64"});  // its own server: no scene loaded before
  v1::LoadSceneRequest request;
  request.set_builtin_scene("demo");
  grpc::ClientContext context;
  v1::LoadSceneResponse response;
  grpc::Status status = stub_->LoadScene(&context, request, &response);
  ASSERT_TRUE(status.ok()) << status.error_message();
  EXPECT_EQ(response.scene_id().size(), 64u);
  EXPECT_GT(response.polygons(), 1000u);
  const v1::Camera expected = CameraToProto(DemoCamera());
  EXPECT_EQ(response.default_camera().SerializeAsString(), expected.SerializeAsString());
  EXPECT_TRUE(Render(FrameRequest(response.scene_id(), 32, 24), 30).ok());

  // Loaded again, the same request is answered from the scene store (not rebuilt):
  // the same id, camera and polygons, in a fraction of the build's time.
  grpc::ClientContext again_context;
  v1::LoadSceneResponse again;
  status = stub_->LoadScene(&again_context, request, &again);
  ASSERT_TRUE(status.ok()) << status.error_message();
  EXPECT_EQ(again.scene_id(), response.scene_id());
  EXPECT_EQ(again.polygons(), response.polygons());
  EXPECT_EQ(again.default_camera().SerializeAsString(), expected.SerializeAsString());
  EXPECT_LT(again.build_ms(), 0.2 * response.build_ms())
      << "first " << response.build_ms() << " ms, again " << again.build_ms() << " ms";

  v1::LoadSceneRequest unknown;
  unknown.set_builtin_scene("moon");
  grpc::ClientContext context2;
  status = stub_->LoadScene(&context2, unknown, &response);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(status.error_message(), HasSubstr("builtin_scene: unknown built-in scene 'moon'"));

  v1::LoadSceneRequest both = request;
  both.mutable_scene()->set_name("also a scene");
  grpc::ClientContext context3;
  status = stub_->LoadScene(&context3, both, &response);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(status.error_message(), HasSubstr("not both"));
}

TEST_F(ServiceTest, RenderFrameReturnsExrAndTimings) {
  StartServer();
  const std::string scene_id = LoadDemoScene();
  const uint64_t rendered_before = Info().frames_rendered();
  v1::RenderFrameResponse response;
  const grpc::Status status = Render(FrameRequest(scene_id, 96, 64), 30, &response);
  ASSERT_TRUE(status.ok()) << status.error_message();
  EXPECT_EQ(response.width(), 96u);
  EXPECT_EQ(response.height(), 64u);
  ASSERT_GT(response.exr().size(), 4u);
  EXPECT_EQ(response.exr().substr(0, 4), std::string("\x76\x2f\x31\x01", 4));  // EXR magic
  EXPECT_GT(response.timings().raster_ms(), 0);
  EXPECT_GE(response.timings().total_ms(), response.timings().raster_ms());
  EXPECT_EQ(Info().frames_rendered(), rendered_before + 1);
}

// A 1 x 1 frame of the demo puts the whole scene in one pixel (1,460 polygons in four
// cells). It took 10-17 s and held a render slot past any deadline; now it must come back within
// its 200 ms deadline (rendered or DEADLINE_EXCEEDED), and the next frame must not wait.
TEST_F(ServiceTest, WholeSceneInOnePixelKeepsItsDeadlineAndBlocksNothing) {
  StartServer();
  const std::string scene_id = LoadDemoScene();
  for (const auto& [width, height] : {std::pair{1, 1}, std::pair{640, 1}}) {
    const auto start = std::chrono::steady_clock::now();
    v1::RenderFrameResponse tiny;
    const grpc::Status status = Render(FrameRequest(scene_id, width, height), 0.2, &tiny);
    const double tiny_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    EXPECT_TRUE(status.ok() || status.error_code() == grpc::StatusCode::DEADLINE_EXCEEDED)
        << status.error_message();
    if (status.ok()) {
      EXPECT_EQ(tiny.width(), static_cast<uint32_t>(width));
    }
    EXPECT_LT(tiny_ms, 1000) << width << "x" << height;
  }
  const auto start = std::chrono::steady_clock::now();
  v1::RenderFrameResponse response;
  const grpc::Status status = Render(FrameRequest(scene_id, 320, 180), 30, &response);
  ASSERT_TRUE(status.ok()) << status.error_message();
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
}

TEST_F(ServiceTest, RenderFrameRegionReturnsOnlyTheRegion) {
  StartServer();
  v1::RenderFrameRequest request = FrameRequest(LoadDemoScene(), 96, 64);
  request.mutable_region()->set_x(16);
  request.mutable_region()->set_y(8);
  request.mutable_region()->set_width(40);
  request.mutable_region()->set_height(24);
  v1::RenderFrameResponse response;
  ASSERT_TRUE(Render(request, 30, &response).ok());
  EXPECT_EQ(response.width(), 40u);
  EXPECT_EQ(response.height(), 24u);

  request.mutable_region()->set_x(80);  // 80 + 40 > 96
  const grpc::Status status = Render(request, 30);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(status.error_message(), HasSubstr("region"));
}

TEST_F(ServiceTest, RenderFrameErrors) {
  StartServer();  // --max-pixels=1000000
  const std::string scene_id = LoadDemoScene();
  const uint64_t failed_before = Info().frames_failed();

  grpc::Status status = Render(FrameRequest(std::string(64, '0'), 32, 32), 10);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::NOT_FOUND);
  EXPECT_THAT(status.error_message(), HasSubstr("scene_id"));

  v1::RenderFrameRequest nan_camera = FrameRequest(scene_id, 32, 32);
  nan_camera.mutable_camera()->mutable_position()->set_y(std::nan(""));
  status = Render(nan_camera, 10);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(status.error_message(), HasSubstr("camera position"));

  status = Render(FrameRequest(scene_id, 1000, 1001), 10);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(status.error_message(), HasSubstr("--max-pixels"));

  status = Render(FrameRequest(scene_id, 0, 32), 10);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(status.error_message(), HasSubstr("options.width"));

  v1::RenderFrameRequest bad_enum = FrameRequest(scene_id, 32, 32);
  bad_enum.mutable_options()->set_anti_aliasing(static_cast<v1::AntiAliasing>(42));
  status = Render(bad_enum, 10);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(status.error_message(), HasSubstr("options.anti_aliasing"));
  EXPECT_EQ(Info().frames_failed(), failed_before + 5);
}

// A scene id that is not one LoadScene returns is INVALID_ARGUMENT naming what is wrong with it,
// whatever its length (a 100 KB id quoted back whole once overflowed the answer's trailers, and
// the client saw RESOURCE_EXHAUSTED); a well-formed unknown one is NOT_FOUND. Every RPC that
// takes a scene id answers alike, and a long client string quoted in any error stays short.
TEST_F(ServiceTest, MalformedSceneIdsAreInvalidAndUnknownOnesNotFound) {
  StartServer();
  const std::string known = LoadDemoScene();
  struct Case {
    std::string id;
    grpc::StatusCode code;
    std::string says;
  };
  const std::vector<Case> cases = {
      {std::string(100 << 10, 'a'), grpc::StatusCode::INVALID_ARGUMENT, "102400 characters"},
      {"no-such-scene", grpc::StatusCode::INVALID_ARGUMENT, "13 characters"},
      {"", grpc::StatusCode::INVALID_ARGUMENT, "scene_id is empty"},
      {std::string(63, 'a') + "G", grpc::StatusCode::INVALID_ARGUMENT, "character 64"},
      {std::string(64, 'f'), grpc::StatusCode::NOT_FOUND, "is not loaded"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.id.substr(0, 70));
    v1::RenderFrameResponse frame;
    grpc::Status status = Render(FrameRequest(c.id, 16, 16), 10, &frame);
    EXPECT_EQ(status.error_code(), c.code) << status.error_message().substr(0, 300);
    EXPECT_THAT(status.error_message(), HasSubstr(c.says));
    EXPECT_LT(status.error_message().size(), 2000u);

    v1::PlanRegionsRequest plan_request;
    plan_request.set_scene_id(c.id);
    *plan_request.mutable_camera() = FrameRequest(known, 16, 16).camera();
    *plan_request.mutable_options() = FrameRequest(known, 16, 16).options();
    plan_request.set_regions(2);
    v1::PlanRegionsResponse plan;
    grpc::ClientContext plan_context;
    status = stub_->PlanRegions(&plan_context, plan_request, &plan);
    EXPECT_EQ(status.error_code(), c.code) << status.error_message().substr(0, 300);
    EXPECT_THAT(status.error_message(), HasSubstr(c.says));

    grpc::ClientContext stream_context;
    auto stream = stub_->RenderStream(&stream_context);
    ASSERT_TRUE(stream->Write(FrameRequest(c.id, 16, 16)));
    stream->WritesDone();
    const std::vector<v1::RenderFrameResponse> answers = ReadAllAnswers(*stream);
    ASSERT_EQ(answers.size(), 1u);
    EXPECT_EQ(answers[0].status_code(), static_cast<uint32_t>(c.code));
    EXPECT_THAT(answers[0].status_message(), HasSubstr(c.says));
    EXPECT_TRUE(stream->Finish().ok());
  }
  // A long object name in a scene update is quoted back cut, not whole.
  v1::RenderFrameRequest update = FrameRequest(known, 16, 16);
  update.mutable_update()->add_objects()->set_name(std::string(100 << 10, 'o'));
  const grpc::Status status = Render(update, 10);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT)
      << status.error_message().substr(0, 300);
  EXPECT_THAT(status.error_message(), HasSubstr("no object of that name"));
  EXPECT_LT(status.error_message().size(), 2000u);
  // The server's log quotes the ids cut too.
  EXPECT_EQ(server_->Log().find(std::string(1000, 'a')), std::string::npos);
}

TEST_F(ServiceTest, OversizedMessageIsRefused) {
  StartServer();  // --max-message-mb=2
  v1::LoadSceneRequest request;
  request.mutable_scene()->set_name(std::string(3 << 20, 'n'));
  grpc::ClientContext context;
  v1::LoadSceneResponse response;
  const grpc::Status status = stub_->LoadScene(&context, request, &response);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
}

// One request at a time (the host waits for each frame): every camera is rendered, in order,
// and a bad one fails alone.
TEST_F(ServiceTest, RenderStreamAnswersEveryCameraInOrder) {
  StartServer();
  const std::string scene_id = LoadDemoScene();
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(60));
  auto stream = stub_->RenderStream(&context);
  constexpr int kFrames = 4;
  std::vector<v1::RenderFrameResponse> frames;
  v1::RenderFrameResponse response;
  for (int i = 0; i < kFrames; ++i) {
    v1::RenderFrameRequest request = FrameRequest(scene_id, 48, 32);
    request.set_frame_index(100 + i);
    request.mutable_camera()->mutable_position()->set_z(request.camera().position().z() - i);
    if (i == 2) request.mutable_camera()->set_yaw_deg(std::nan(""));  // fails alone
    ASSERT_TRUE(stream->Write(request));
    ASSERT_TRUE(stream->Read(&response));
    frames.push_back(response);
  }
  stream->WritesDone();
  EXPECT_FALSE(stream->Read(&response));
  ASSERT_TRUE(stream->Finish().ok());
  ASSERT_EQ(frames.size(), static_cast<size_t>(kFrames));
  for (int i = 0; i < kFrames; ++i) {
    EXPECT_EQ(frames[i].frame_index(), 100u + i);
    if (i == 2) {
      EXPECT_EQ(frames[i].status_code(), static_cast<int>(grpc::StatusCode::INVALID_ARGUMENT));
      EXPECT_THAT(frames[i].status_message(), HasSubstr("camera"));
    } else {
      EXPECT_EQ(frames[i].status_code(), 0) << frames[i].status_message();
      EXPECT_EQ(frames[i].width(), 48u);
      EXPECT_FALSE(frames[i].exr().empty());
    }
  }
}

// The newest state wins: a burst of 20 requests to a server that renders slowly (1920x1080 on
// one thread) is answered 20 times in order; the requests that were still waiting when a newer
// one came are skipped, naming the newer frame, and the newest is always rendered.
TEST_F(ServiceTest, RenderStreamSkipsSupersededRequestsAndRendersTheNewest) {
  StartServer({"--threads=1"});
  const std::string scene_id = LoadDemoScene();
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(120));
  auto stream = stub_->RenderStream(&context);
  constexpr int kFrames = 20;
  for (int i = 0; i < kFrames; ++i) {
    v1::RenderFrameRequest request = FrameRequest(scene_id, 1920, 1080);
    request.set_frame_index(i);
    ASSERT_TRUE(stream->Write(request));
  }
  stream->WritesDone();
  const std::vector<v1::RenderFrameResponse> frames = ReadAllAnswers(*stream);
  ASSERT_TRUE(stream->Finish().ok());
  ASSERT_EQ(frames.size(), static_cast<size_t>(kFrames));
  int rendered = 0;
  for (int i = 0; i < kFrames; ++i) {
    const v1::RenderFrameResponse& f = frames[i];
    EXPECT_EQ(f.frame_index(), static_cast<uint64_t>(i));
    EXPECT_EQ(f.status_code(), 0) << f.status_message();
    if (f.outcome() == v1::FRAME_OUTCOME_RENDERED) {
      ++rendered;
      EXPECT_EQ(f.width(), 1920u);
      EXPECT_FALSE(f.exr().empty());
    } else {
      EXPECT_EQ(f.outcome(), v1::FRAME_OUTCOME_SKIPPED_SUPERSEDED);
      EXPECT_GT(f.superseded_by(), f.frame_index());
      EXPECT_TRUE(f.exr().empty());
    }
  }
  EXPECT_EQ(frames.back().outcome(), v1::FRAME_OUTCOME_RENDERED);
  // The burst arrives within milliseconds, one frame takes over 100 ms: one or two frames can
  // start before the newest is read, plus the newest.
  EXPECT_LE(rendered, 4);
  EXPECT_EQ(Info().frames_skipped(), static_cast<uint64_t>(kFrames - rendered));
}

// A request whose own deadline_ms passes while it waits is skipped as late, never rendered.
TEST_F(ServiceTest, RenderStreamSkipsAFrameTooLateToMatter) {
  StartServer({"--threads=1"});
  const std::string scene_id = LoadDemoScene();
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(120));
  auto stream = stub_->RenderStream(&context);
  v1::RenderFrameRequest slow = FrameRequest(scene_id, 2560, 1440);
  slow.set_frame_index(1);
  v1::RenderFrameRequest late = FrameRequest(scene_id, 64, 64);
  late.set_frame_index(2);
  late.set_deadline_ms(1);  // waits behind the slow frame for far longer than 1 ms
  ASSERT_TRUE(stream->Write(slow));
  // The slow frame (about 150 ms of raster on one thread) has started; had the late one come at
  // once, it would have superseded the slow one instead.
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  ASSERT_TRUE(stream->Write(late));
  stream->WritesDone();
  const std::vector<v1::RenderFrameResponse> frames = ReadAllAnswers(*stream);
  ASSERT_TRUE(stream->Finish().ok());
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[0].outcome(), v1::FRAME_OUTCOME_RENDERED);
  EXPECT_FALSE(frames[0].exr().empty());
  EXPECT_EQ(frames[1].frame_index(), 2u);
  EXPECT_EQ(frames[1].outcome(), v1::FRAME_OUTCOME_SKIPPED_LATE);
  EXPECT_TRUE(frames[1].exr().empty());
}

TEST_F(ServiceTest, ServerInfoReportsLimits) {
  StartServer({"--threads=2", "--max-queue=5", "--concurrent-frames=1"});
  const v1::GetServerInfoResponse info = Info();
  EXPECT_EQ(info.threads(), 2u);
  EXPECT_EQ(info.max_queue(), 5u);
  EXPECT_EQ(info.concurrent_frames(), 1u);
  EXPECT_GE(info.uptime_s(), 0);
}

}  // namespace
}  // namespace aperture::testing
