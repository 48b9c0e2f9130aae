// The shared-memory texture store seen from the service: servers on one machine share
// what any of them (or `aperture-tex bake`) built, and an entry cut short by a crash is rebuilt,
// never used.
#include <fcntl.h>
#include <gmock/gmock.h>
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "absl/strings/str_cat.h"
#include "aperture/v1/render_service.grpc.pb.h"
#include "frame/camera_proto.h"
#include "integration/server_process.h"
#include "scene/scene_builder.h"
#include "scene/scene_file.h"
#include "testing/curved_scenes.h"
#include "texture/image_file.h"
#include "texture/summed_area_table.h"

namespace aperture::testing {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

// A textured ground plane whose material asks for seed 000's table (aniso): loading it makes the
// server build (or attach) the table of a `texels`^2 checkerboard.
v1::Scene AnisoGroundScene(int texels) {
  v1::Scene scene;
  scene.set_name("aniso-ground");
  v1::Texture& texture = *scene.add_textures();
  texture.set_id("checker");
  texture.mutable_checkerboard()->set_size(static_cast<uint32_t>(texels));
  texture.mutable_checkerboard()->set_cells(8);
  v1::Material& material = *scene.add_materials();
  material.set_id("ground");
  material.set_texture_id("checker");
  material.mutable_texture_transform()->set_repeat_u(4);
  material.set_filter(v1::TEXTURE_FILTER_ANISO);
  v1::Mesh& mesh = *scene.add_meshes();
  mesh.set_id("ground");
  mesh.set_material_id("ground");
  v1::Polygon& polygon = *mesh.add_polygons();
  for (const auto& [x, z] :
       {std::pair{-500.0, 500.0}, {500.0, 500.0}, {500.0, -500.0}, {-500.0, -500.0}}) {
    v1::Vec3& v = *polygon.add_vertices();
    v.set_x(x);
    v.set_z(z);
  }
  scene.add_objects()->set_mesh_id("ground");
  return scene;
}

class Connection {
 public:
  explicit Connection(const ServerProcess& server) {
    grpc::ChannelArguments args;
    args.SetMaxReceiveMessageSize(-1);
    stub_ = v1::Render::NewStub(
        grpc::CreateCustomChannel(server.address(), grpc::InsecureChannelCredentials(), args));
  }

  grpc::Status LoadScene(const v1::Scene& scene, std::string* id) {
    grpc::ClientContext context;
    context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(120));
    v1::LoadSceneRequest request;
    *request.mutable_scene() = scene;
    v1::LoadSceneResponse response;
    const grpc::Status status = stub_->LoadScene(&context, request, &response);
    *id = response.scene_id();
    return status;
  }

  v1::StoreInfo Store() {
    grpc::ClientContext context;
    context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(10));
    v1::GetServerInfoResponse response;
    EXPECT_TRUE(stub_->GetServerInfo(&context, {}, &response).ok());
    return response.store();
  }

  std::string RenderExr(const std::string& scene_id, const v1::Camera* camera = nullptr,
                        v1::RenderMode mode = v1::RENDER_MODE_RASTER) {
    v1::RenderFrameRequest request;
    request.set_scene_id(scene_id);
    request.mutable_options()->set_mode(mode);
    request.mutable_camera()->mutable_position()->set_y(1);
    request.mutable_camera()->set_pitch_deg(-5);
    if (camera != nullptr) *request.mutable_camera() = *camera;
    request.mutable_options()->set_width(160);
    request.mutable_options()->set_height(120);
    grpc::ClientContext context;
    context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(60));
    v1::RenderFrameResponse response;
    const grpc::Status status = stub_->RenderFrame(&context, request, &response);
    EXPECT_TRUE(status.ok()) << status.error_message();
    return response.exr();
  }

 private:
  std::unique_ptr<v1::Render::Stub> stub_;
};

class SharedStoreServiceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    store_ = fs::path(::testing::TempDir()) /
             ("aperture_shared_store_" + std::to_string(getpid()) + "_" +
              ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(store_);
  }
  void TearDown() override { fs::remove_all(store_); }

  std::unique_ptr<ServerProcess> Start() {
    std::string error;
    auto server = ServerProcess::Start({"--store=" + store_.string(), "--threads=2"}, &error);
    EXPECT_NE(server, nullptr) << error;
    return server;
  }

  // Writes the scene as a scene file for `aperture-tex bake`.
  std::string WriteSceneFile(const v1::Scene& scene) {
    const fs::path path = fs::path(::testing::TempDir()) /
                          ("aperture_bake_scene_" + std::to_string(getpid()) + ".json");
    std::ofstream(path) << SceneToJson(scene);
    return path.string();
  }

  fs::path store_;
};

TEST_F(SharedStoreServiceTest, ATableBuiltByOneServerIsMappedNotRebuiltByTheOther) {
  auto first = Start();
  auto second = Start();
  ASSERT_TRUE(first && second);
  Connection a(*first), b(*second);
  const v1::Scene scene = AnisoGroundScene(256);

  std::string id_a, id_b;
  ASSERT_TRUE(a.LoadScene(scene, &id_a).ok());
  const v1::StoreInfo after_first = a.Store();
  EXPECT_EQ(after_first.directory(), store_.string());
  EXPECT_EQ(after_first.entries_built(), 1u) << "the table of the one aniso texture";

  ASSERT_TRUE(b.LoadScene(scene, &id_b).ok());
  const v1::StoreInfo after_second = b.Store();
  EXPECT_EQ(after_second.entries_built(), 0u) << "the second server must not rebuild it";
  EXPECT_EQ(after_second.entries_attached(), 1u);

  // Both render from the same bytes in shared memory: the same pixels (the EXR headers differ in
  // their render times).
  const std::string exr_a = a.RenderExr(id_a), exr_b = b.RenderExr(id_b);
  auto decode = [](const std::string& exr) {
    return DecodeImage({reinterpret_cast<const uint8_t*>(exr.data()), exr.size()});
  };
  auto image_a = decode(exr_a), image_b = decode(exr_b);
  ASSERT_TRUE(image_a.ok() && image_b.ok());
  ASSERT_EQ(image_a->texels().size(), image_b->texels().size());
  ASSERT_EQ(image_a->width(), 160);
  for (size_t i = 0; i < image_a->texels().size(); ++i) {
    const Rgba& p = image_a->texels()[i];
    const Rgba& q = image_b->texels()[i];
    ASSERT_TRUE(p.r == q.r && p.g == q.g && p.b == q.b && p.a == q.a) << "pixel " << i;
  }
}

// Seed 003's summed-area tables live in the store too: built by the first server's
// first raytraced frame, mapped by the second.
TEST_F(SharedStoreServiceTest, RaytraceTablesBuiltByOneServerAreMappedByTheOther) {
  auto first = Start();
  auto second = Start();
  ASSERT_TRUE(first && second);
  Connection a(*first), b(*second);
  const CurvedTestScene test = MakeCurvedTestScene(CurvedSceneKind::kSphere, 128);
  const v1::Camera camera = CameraToProto(test.camera);
  std::string id_a, id_b;
  ASSERT_TRUE(a.LoadScene(test.scene, &id_a).ok());
  ASSERT_TRUE(b.LoadScene(test.scene, &id_b).ok());
  EXPECT_EQ(a.Store().entries_built(), 0u) << "no table before a raytraced frame";

  const std::string exr_a = a.RenderExr(id_a, &camera, v1::RENDER_MODE_RAYTRACE);
  EXPECT_EQ(a.Store().entries_built(), 1u) << "the checkerboard's summed-area tables";
  const std::string exr_b = b.RenderExr(id_b, &camera, v1::RENDER_MODE_RAYTRACE);
  EXPECT_EQ(b.Store().entries_built(), 0u) << "the second server must not rebuild them";
  EXPECT_EQ(b.Store().entries_attached(), 1u);
  bool listed = false;
  for (const auto& item : fs::directory_iterator(store_))
    listed = listed || item.path().filename().string().rfind(
                           absl::StrCat("sat-v", kSummedAreaTableVersion, "-c3-"), 0) == 0;
  EXPECT_TRUE(listed);

  auto decode = [](const std::string& exr) {
    return DecodeImage({reinterpret_cast<const uint8_t*>(exr.data()), exr.size()});
  };
  auto image_a = decode(exr_a), image_b = decode(exr_b);
  ASSERT_TRUE(image_a.ok() && image_b.ok());
  ASSERT_EQ(image_a->texels().size(), image_b->texels().size());
  float sum = 0;
  for (size_t i = 0; i < image_a->texels().size(); ++i) {
    const Rgba& p = image_a->texels()[i];
    const Rgba& q = image_b->texels()[i];
    ASSERT_TRUE(p.r == q.r && p.g == q.g && p.b == q.b) << "pixel " << i;
    sum += p.r;
  }
  EXPECT_GT(sum, 100.0f) << "the sphere is drawn";
}

TEST_F(SharedStoreServiceTest, ARestartedServerReattachesToWhatTheStoreHolds) {
  const v1::Scene scene = AnisoGroundScene(256);
  std::string id;
  {
    auto server = Start();
    ASSERT_TRUE(server);
    Connection c(*server);
    ASSERT_TRUE(c.LoadScene(scene, &id).ok());
    EXPECT_EQ(c.Store().entries_built(), 1u);
  }  // SIGKILL
  auto restarted = Start();
  ASSERT_TRUE(restarted);
  Connection c(*restarted);
  ASSERT_TRUE(c.LoadScene(scene, &id).ok());
  EXPECT_EQ(c.Store().entries_built(), 0u);
  EXPECT_EQ(c.Store().entries_attached(), 1u);
}

TEST_F(SharedStoreServiceTest, BakeFillsTheStoreAheadOfTheServer) {
  const std::string scene_file = WriteSceneFile(AnisoGroundScene(256));
  const CommandResult bake =
      RunCommand({APERTURE_TEX_BIN, "bake", scene_file, "--store", store_.string()}, 120);
  ASSERT_EQ(bake.exit_code, 0) << bake.err;
  EXPECT_THAT(bake.out, HasSubstr("texture 'checker' (256x256): table ready"));
  EXPECT_THAT(bake.out, HasSubstr("1 entries built, 0 already stored"));

  const CommandResult again =
      RunCommand({APERTURE_TEX_BIN, "bake", scene_file, "--store", store_.string()}, 120);
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_THAT(again.out, HasSubstr("0 entries built, 1 already stored"));

  auto server = Start();
  ASSERT_TRUE(server);
  Connection c(*server);
  std::string id;
  ASSERT_TRUE(c.LoadScene(AnisoGroundScene(256), &id).ok());
  EXPECT_EQ(c.Store().entries_built(), 0u);
  EXPECT_EQ(c.Store().entries_attached(), 1u);
  fs::remove(scene_file);
}

TEST_F(SharedStoreServiceTest, ABakeKilledMidBuildLeavesNothingARestartUsesWithoutRebuilding) {
  // Large enough that the build lasts well beyond the moment its temporary entry appears.
  const std::string scene_file = WriteSceneFile(AnisoGroundScene(1024));
  const pid_t pid = fork();
  if (pid == 0) {
    const int null = open("/dev/null", O_WRONLY);
    dup2(null, 1);
    dup2(null, 2);
    execl(APERTURE_TEX_BIN, APERTURE_TEX_BIN, "bake", scene_file.c_str(), "--store", store_.c_str(),
          static_cast<char*>(nullptr));
    _exit(127);
  }
  // Kill it once its temporary entry exists, i.e. in the middle of building the table.
  bool building = false;
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!building && std::chrono::steady_clock::now() < give_up) {
    std::error_code error;
    for (const auto& item : fs::directory_iterator(store_, error))
      if (item.path().filename().string().find(".entry.tmp.") != std::string::npos) building = true;
    if (!building) std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(building) << "the bake never started writing an entry";
  ASSERT_TRUE(WIFSIGNALED(status)) << "the bake finished before it could be killed";

  auto server = Start();
  ASSERT_TRUE(server);
  Connection c(*server);
  std::string id;
  ASSERT_TRUE(c.LoadScene(AnisoGroundScene(1024), &id).ok());
  EXPECT_EQ(c.Store().entries_attached(), 0u) << "nothing of the killed bake may be used";
  EXPECT_EQ(c.Store().entries_built(), 1u);
  for (const auto& item : fs::directory_iterator(store_))
    EXPECT_EQ(item.path().filename().string().find(".entry.tmp."), std::string::npos)
        << "left over: " << item.path();
  fs::remove(scene_file);
}

TEST_F(SharedStoreServiceTest, AStoreDirectoryThatCannotBeCreatedIsAClearStartupError) {
  const CommandResult result =
      RunCommand({APERTURE_SERVER_BIN, "--listen=127.0.0.1:0", "--store=/proc/aperture-store"}, 20);
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_THAT(result.err, HasSubstr("--store /proc/aperture-store"));
}

}  // namespace
}  // namespace aperture::testing
