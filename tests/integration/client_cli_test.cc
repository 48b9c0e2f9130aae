// The `aperture` client against real servers: the frame it receives has the same pixels as the
// one aperture-render writes locally; textures already on the server are not sent again; health,
// load and sim run end to end; a batch survives a killed server and resumes without rework; a job
// split with --shard I/N renders each frame in exactly one shard, and --check finds the gaps.
// Protobuf's headers before OpenImageIO's, whose farmhash.h #undefs the bswap_32 and bswap_64
// that protobuf's port.h needs.
// clang-format off
#include <google/protobuf/util/json_util.h>
#include <grpcpp/grpcpp.h>
#include "aperture/v1/render_service.grpc.pb.h"
// clang-format on
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <future>
#include <iterator>
#include <thread>
#include <vector>

#include "aperture/v1/client_reports.pb.h"
#include "integration/server_process.h"
#include "integration/service_fixture.h"
#include "support/exr_pixels.h"
#include "support/gltf_test_models.h"

namespace aperture::testing {
namespace {

using ::testing::HasSubstr;

class ClientTest : public ::testing::Test {
 protected:
  // One server for the suite; a test that stops it starts its own.
  static void TearDownTestSuite() { shared_server_.reset(); }
  void SetUp() override {
    std::string error;
    if (!shared_server_) shared_server_ = ServerProcess::Start({}, &error);
    ASSERT_NE(shared_server_, nullptr) << error;
    server_ = shared_server_.get();
    dir_ = std::filesystem::temp_directory_path() /
           ("aperture_client_test_" + std::to_string(getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  CommandResult Client(std::vector<std::string> args) {
    args.insert(args.begin(), APERTURE_CLIENT_BIN);
    args.push_back("--server=" + server_->address());
    return RunCommand(args, 60);
  }

  static std::unique_ptr<ServerProcess> shared_server_;
  ServerProcess* server_ = nullptr;
  std::filesystem::path dir_;
};

std::unique_ptr<ServerProcess> ClientTest::shared_server_;

// A ground plane textured with a small PNG file: the client uploads the file's bytes.
std::string WriteGroundScene(const std::filesystem::path& dir) {
  OIIO::ImageSpec spec(16, 16, 3, OIIO::TypeDesc::UINT8);
  OIIO::ImageBuf grid(spec);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const float v = ((x / 4 + y / 4) % 2) ? 1.0f : 0.2f;
      const float pixel[3] = {v, v * 0.9f, v * 0.5f};
      grid.setpixel(x, y, pixel);
    }
  grid.write((dir / "grid.png").string());
  const std::string path = (dir / "ground.json").string();
  std::ofstream(path) << R"({"name": "ground",
    "textures": [{"id": "grid", "file": "grid.png"}],
    "materials": [{"id": "g", "textureId": "grid", "textureTransform": {"repeatU": 4}}],
    "meshes": [{"id": "ground", "materialId": "g", "polygons": [{"vertices": [
      {"x": -500, "y": 0, "z": -500}, {"x": -500, "y": 0, "z": 500},
      {"x": 500, "y": 0, "z": 500}, {"x": 500, "y": 0, "z": -500}]}]}],
    "objects": [{"meshId": "ground"}]})";
  return path;
}

// The --json report on the command's stdout, read with protobuf's JSON parser (unknown fields
// refused: the output must match its schema, proto/aperture/v1/client_reports.proto).
template <typename Report>
Report ParseReport(const std::string& out) {
  Report report;
  const auto status = google::protobuf::util::JsonStringToMessage(out, &report);
  EXPECT_TRUE(status.ok()) << status.ToString() << "\n" << out;
  return report;
}

TEST_F(ClientTest, FrameEqualsWhatApertureRenderWrites) {
  const std::vector<std::string> frame_flags = {"--size=160x96", "--camera=0,20,300,5,-6,1",
                                                "--aa=tent2", "--filter=trilinear",
                                                "--compression=piz"};
  std::vector<std::string> local = {
      APERTURE_RENDER_BIN, "--scene=demo", "--nopreview",
      "--threads=2",       "-o",           (dir_ / "local.exr").string()};
  local.insert(local.end(), frame_flags.begin(), frame_flags.end());
  const CommandResult rendered = RunCommand(local, 60);
  ASSERT_EQ(rendered.exit_code, 0) << rendered.err;

  std::vector<std::string> remote = {"render", "--scene=demo",
                                     "-o=" + (dir_ / "remote.exr").string()};
  remote.insert(remote.end(), frame_flags.begin(), frame_flags.end());
  const CommandResult first = Client(remote);
  ASSERT_EQ(first.exit_code, 0) << first.err;
  // The server builds the built-in demo itself: nothing to upload.
  EXPECT_THAT(first.out, HasSubstr("textures uploaded 0, already on the server 0"));

  int lw = 0, lh = 0, rw = 0, rh = 0;
  const std::vector<float> a = ReadPixels((dir_ / "local.exr").string(), &lw, &lh);
  const std::vector<float> b = ReadPixels((dir_ / "remote.exr").string(), &rw, &rh);
  ASSERT_FALSE(a.empty());
  EXPECT_EQ(lw, 160);
  EXPECT_EQ(lh, 96);
  EXPECT_EQ(rw, lw);
  EXPECT_EQ(rh, lh);
  EXPECT_TRUE(a == b) << "the service's pixels differ from aperture-render's";
}

// Every built-in scene is a name the server builds, from `aperture render` and from a batch job
// alike (a job's scene was once taken for a file beside the job unless it was "demo").
TEST_F(ClientTest, BuiltinScenesByNameRenderAsTheyDoLocally) {
  for (const std::string scene : {"airport", "tris-40"}) {
    const std::string local = (dir_ / ("local-" + scene + ".exr")).string();
    const CommandResult rendered =
        RunCommand({APERTURE_RENDER_BIN, "--scene=" + scene, "--size=96x54", "--nopreview",
                    "--threads=2", "-o", local},
                   60);
    ASSERT_EQ(rendered.exit_code, 0) << rendered.err;
    const std::string remote = (dir_ / ("remote-" + scene + ".exr")).string();
    const CommandResult served =
        Client({"render", "--scene=" + scene, "--size=96x54", "-o=" + remote});
    ASSERT_EQ(served.exit_code, 0) << scene << ": " << served.err;
    EXPECT_THAT(served.out, HasSubstr("textures uploaded 0, already on the server 0"));
    int lw = 0, lh = 0, rw = 0, rh = 0;
    const std::vector<float> a = ReadPixels(local, &lw, &lh);
    ASSERT_FALSE(a.empty());
    EXPECT_TRUE(a == ReadPixels(remote, &rw, &rh)) << scene << ": the service's pixels differ";
  }
  const std::filesystem::path jobs = dir_ / "builtin_jobs";
  std::filesystem::create_directories(jobs);
  const std::string job = (jobs / "tris.json").string();
  std::ofstream(job) << R"({"scene": "tris-40", "size": "48x27",
      "path": {"from": "0,1.7,0,0,-10,0", "to": "0,1.7,-50,0,-10,0", "frames": 2}})";
  const CommandResult batch =
      RunCommand({APERTURE_CLIENT_BIN, "batch", job, "--servers=" + server_->address(),
                  "-o=" + (jobs / "frames").string(), "--nocontact_sheet"},
                 60);
  EXPECT_EQ(batch.exit_code, 0) << batch.out << batch.err;
  EXPECT_THAT(batch.out, HasSubstr("2 rendered"));
}

// A scene file cannot make the client upload files outside its folder.
TEST_F(ClientTest, TexturePathsOutsideTheSceneFilesFolderAreRefused) {
  const std::filesystem::path folder = dir_ / "scenes";
  std::filesystem::create_directories(folder);
  // An image beside the folder, not in it (its own content: other tests upload theirs).
  OIIO::ImageBuf outside(OIIO::ImageSpec(8, 8, 3, OIIO::TypeDesc::UINT8));
  const float grey[3] = {0.3f, 0.3f, 0.3f};
  OIIO::ImageBufAlgo::fill(outside, grey);
  ASSERT_TRUE(outside.write((dir_ / "outside.png").string()));
  const std::string quad = R"("meshes": [{"id": "g", "materialId": "m", "polygons": [{"vertices": [
      {"x": -50, "z": -50}, {"x": -50, "z": 50}, {"x": 50, "z": 50}, {"x": 50, "z": -50}]}]}])";
  auto scene_naming = [&](const std::string& name, const std::string& file) {
    const std::string path = (folder / name).string();
    std::ofstream(path) << R"({"textures": [{"id": "t", "file": ")" << file
                        << R"("}], "materials": [{"id": "m", "textureId": "t"}], )" << quad << "}";
    return path;
  };
  std::filesystem::create_symlink(dir_ / "outside.png", folder / "link.png");
  const std::vector<std::string> frame = {"--size=16x16", "--camera=0,1.7,0,0,-10,0",
                                          "-o=" + (dir_ / "path.exr").string()};
  for (const auto& [name, file] : {std::pair<std::string, std::string>{"up.json", "../outside.png"},
                                   {"absolute.json", (dir_ / "outside.png").string()},
                                   {"link.json", "link.png"},
                                   {"passwd.json", "../../../../../../../etc/passwd"}}) {
    SCOPED_TRACE(name);
    std::vector<std::string> args = {"render", "--scene=" + scene_naming(name, file)};
    args.insert(args.end(), frame.begin(), frame.end());
    const CommandResult refused = Client(args);
    EXPECT_EQ(refused.exit_code, 2);  // bad input: the scene file's
    EXPECT_THAT(refused.err, HasSubstr("outside the scene file's folder"));
    EXPECT_THAT(refused.err, HasSubstr("--allow-any-path"));
  }
  std::vector<std::string> allowed = {"render", "--scene=" + (folder / "up.json").string(),
                                      "--allow-any-path"};
  allowed.insert(allowed.end(), frame.begin(), frame.end());
  const CommandResult uploaded = Client(allowed);
  EXPECT_EQ(uploaded.exit_code, 0) << uploaded.err;
}

TEST_F(ClientTest, ASceneFilesTexturesAreUploadedOnceThenFoundOnTheServer) {
  const std::vector<std::string> render = {"render", "--scene=" + WriteGroundScene(dir_),
                                           "--camera=0,1.7,0,0,-10,0", "--size=64x48",
                                           "-o=" + (dir_ / "ground.exr").string()};
  const CommandResult first = Client(render);
  ASSERT_EQ(first.exit_code, 0) << first.err;
  EXPECT_THAT(first.out, HasSubstr("textures uploaded 1, already on the server 0"));
  // The second render finds the texture on the server and sends none.
  const CommandResult second = Client(render);
  ASSERT_EQ(second.exit_code, 0) << second.err;
  EXPECT_THAT(second.out, HasSubstr("textures uploaded 0, already on the server 1"));
}

// A glTF model through the client, its image uploaded content-addressed (an external
// file from the .gltf, bytes of the buffer from the .glb), gives aperture-render's pixels.
TEST_F(ClientTest, AGltfModelRendersAsItDoesLocally) {
  const CommandResult made =
      RunCommand({"/usr/bin/env", "python3",
                  std::string(APERTURE_TESTS_DIR) + "/support/make_gltf_fixture.py", dir_.string()},
                 60);
  ASSERT_EQ(made.exit_code, 0) << made.err;
  const std::vector<std::string> frame_flags = {"--size=96x64", "--camera=0,1.7,5,0,-5,0",
                                                "--compression=none"};
  for (const char* model : {"hangar.gltf", "hangar.glb"}) {
    SCOPED_TRACE(model);
    const std::string scene = (dir_ / model).string();
    std::vector<std::string> local = {APERTURE_RENDER_BIN,
                                      "--scene=" + scene,
                                      "--nopreview",
                                      "--fov=60",
                                      "--store=none",
                                      "-o",
                                      (dir_ / "local.exr").string()};
    local.insert(local.end(), frame_flags.begin(), frame_flags.end());
    const CommandResult rendered = RunCommand(local, 60);
    ASSERT_EQ(rendered.exit_code, 0) << rendered.err;
    std::vector<std::string> remote = {"render", "--scene=" + scene,
                                       "-o=" + (dir_ / "remote.exr").string()};
    remote.insert(remote.end(), frame_flags.begin(), frame_flags.end());
    const CommandResult sent = Client(remote);
    ASSERT_EQ(sent.exit_code, 0) << sent.err;
    EXPECT_THAT(sent.out, HasSubstr("textures uploaded"));
    int w = 0, h = 0;
    const std::vector<float> a = ReadPixels((dir_ / "local.exr").string(), &w, &h);
    const std::vector<float> b = ReadPixels((dir_ / "remote.exr").string(), &w, &h);
    ASSERT_FALSE(a.empty());
    EXPECT_TRUE(a == b) << "the service's pixels differ from aperture-render's";
  }
  // The model's camera by name, with its own field of view, as aperture-render takes it.
  const std::string scene = "--scene=" + (dir_ / "hangar.gltf").string();
  const CommandResult local =
      RunCommand({APERTURE_RENDER_BIN, scene, "--camera=gate", "--size=96x64", "--nopreview",
                  "--store=none", "--compression=none", "-o", (dir_ / "gate_local.exr").string()},
                 60);
  ASSERT_EQ(local.exit_code, 0) << local.err;
  const CommandResult sent = Client({"render", scene, "--camera=gate", "--size=96x64",
                                     "--compression=none", "-o=" + (dir_ / "gate.exr").string()});
  ASSERT_EQ(sent.exit_code, 0) << sent.err;
  int w = 0, h = 0;
  EXPECT_TRUE(ReadPixels((dir_ / "gate_local.exr").string(), &w, &h) ==
              ReadPixels((dir_ / "gate.exr").string(), &w, &h));
  const CommandResult unknown =
      Client({"render", scene, "--camera=tower", "-o=" + (dir_ / "x.exr").string()});
  EXPECT_EQ(unknown.exit_code, 2) << unknown.err;
  EXPECT_THAT(unknown.err, HasSubstr("is neither X,Y,Z,YAW,PITCH,ROLL nor a camera of the model "
                                     "(gate)"));
}

// A model whose node graph is not a tree, one over the triangle budget and one of the wrong JSON
// structure are refused by the client before anything is sent: status 2 and the importer's
// message, within 2 GB of address space (the DAG of depth 40 as a tree is 2^40 triangles).
TEST_F(ClientTest, AGltfModelThatIsNotATreeIsRefusedWithStatus2) {
  const std::string bad_array = PrimitivesAsObject();
  const struct {
    const char* file;
    std::string content;
    std::string message;
  } cases[] = {
      {"dag40.gltf", DuplicatedChildDag(40),
       "dag40.gltf: nodes[40]: listed twice as a child by nodes[39]; glTF nodes form a tree"},
      {"cycle.gltf",
       GltfFile(R"([{"mesh": 0}, {"name": "a", "children": [2]}, {"children": [1]}])"),
       "cycle.gltf: nodes[1] ('a'): is its own ancestor"},
      {"budget.gltf", InstancedMesh(20'000, ByteStripMesh(100'000)),
       "budget.gltf: the model's nodes place 2000000000 triangles"},
      {"bad_array.gltf", bad_array, "bad_array.gltf: meshes[0].primitives: expected an array"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.file);
    const std::string path = (dir_ / c.file).string();
    std::ofstream(path) << c.content;
    const CommandResult r = RunCommand(
        {"/bin/sh", "-c", "ulimit -v 2000000; exec \"$0\" \"$@\"", APERTURE_CLIENT_BIN, "render",
         "--scene=" + path, "-o=" + (dir_ / "x.exr").string(), "--server=" + server_->address()},
        60);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_THAT(r.err, HasSubstr("aperture render: error: " + path));
    EXPECT_THAT(r.err, HasSubstr(c.message));
  }
}

// The ground scene with a textured sphere on it: only the raytrace mode draws it.
std::string WriteSphereScene(const std::filesystem::path& dir) {
  const std::string ground = WriteGroundScene(dir);
  std::string text;
  {
    std::ifstream in(ground);
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  text.insert(text.rfind('}'), R"(, "spheres": [{"center": {"x": 0, "y": 1, "z": -6},
    "radius": 1, "materialId": "g"}])");
  const std::string path = (dir / "sphere.json").string();
  std::ofstream(path) << text;
  return path;
}

TEST_F(ClientTest, RaytraceModeFrameEqualsWhatApertureRenderWrites) {
  const std::string scene = WriteSphereScene(dir_);
  const std::vector<std::string> frame_flags = {
      "--scene=" + scene, "--size=80x60", "--camera=0,1.7,0,0,-10,0",
      "--mode=raytrace",  "--delta=0.05", "--max_depth=2"};
  std::vector<std::string> local = {APERTURE_RENDER_BIN, "--nopreview", "--threads=2", "-o",
                                    (dir_ / "local.exr").string()};
  local.insert(local.end(), frame_flags.begin(), frame_flags.end());
  const CommandResult rendered = RunCommand(local, 60);
  ASSERT_EQ(rendered.exit_code, 0) << rendered.err;

  std::vector<std::string> remote = {"render", "-o=" + (dir_ / "remote.exr").string()};
  remote.insert(remote.end(), frame_flags.begin(), frame_flags.end());
  const CommandResult traced = Client(remote);
  ASSERT_EQ(traced.exit_code, 0) << traced.err;

  int lw = 0, lh = 0, rw = 0, rh = 0;
  const std::vector<float> a = ReadPixels((dir_ / "local.exr").string(), &lw, &lh);
  const std::vector<float> b = ReadPixels((dir_ / "remote.exr").string(), &rw, &rh);
  ASSERT_FALSE(a.empty());
  EXPECT_EQ(rw, 80);
  EXPECT_EQ(rh, 60);
  EXPECT_TRUE(a == b) << "the service's raytraced pixels differ from aperture-render's";

  // The same request in raster mode is refused: the sphere needs the raytrace mode.
  remote[remote.size() - 3] = "--mode=raster";
  const CommandResult raster = Client(remote);
  EXPECT_EQ(raster.exit_code, 2);
  EXPECT_THAT(raster.err, HasSubstr("RENDER_MODE_RAYTRACE"));
  const CommandResult unknown = Client({"render", "--mode=pathtrace", "--size=8x8"});
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_THAT(unknown.err, HasSubstr("--mode 'pathtrace' is not one of"));
}

TEST_F(ClientTest, RenderReportsBadInputWithExitStatus2) {
  const CommandResult result =
      Client({"render", "--scene=demo", "--size=64x48", "--camera=nan,1,2,0,0,0",
              "-o=" + (dir_ / "x.exr").string()});
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_THAT(result.err, HasSubstr("camera position is not finite"));
}

// Bad input exits 2 with a message naming the problem, before anything is sent: a scene file
// that is not there, a texture path the client refuses, a deadline that is no deadline, a server
// address where nothing answers or whose name does not resolve; for every command that takes them.
TEST_F(ClientTest, BadInputExitsTwoNamingTheProblem) {
  const std::string texture_outside = (dir_ / "outside.json").string();
  std::ofstream(texture_outside)
      << R"({"textures": [{"id": "t", "file": "../../../../../../etc/passwd"}],
             "materials": [{"id": "m", "textureId": "t"}]})";
  const std::string missing = (dir_ / "no-such-scene.json").string();
  struct Case {
    std::vector<std::string> args;
    std::string says;
  };
  const std::string here = "--server=" + server_->address();
  const std::string nothing_listens = "--server=127.0.0.1:1";
  const std::string misnamed = "--server=nosuchhost.invalid:1";
  const std::string out = "-o=" + (dir_ / "bad.exr").string();
  const std::vector<Case> cases = {
      {{"render", "--scene=" + missing, here, out}, "cannot read " + missing},
      {{"render", "--scene=" + texture_outside, here, out}, "outside the scene file's folder"},
      {{"render", "--scene=demo", "--deadline-s=-1", here, out}, "--deadline-s is -1"},
      {{"render", "--scene=demo", nothing_listens, out}, "cannot reach a server at 127.0.0.1:1"},
      {{"render", "--scene=demo", misnamed, out}, "cannot reach a server at nosuchhost.invalid:1"},
      {{"render", "--split=2", "--servers=127.0.0.1:1", "--scene=demo", out},
       "cannot reach a server at 127.0.0.1:1"},
      {{"load", "--scene=" + missing, "--requests=1", here}, "cannot read " + missing},
      {{"load", "--requests=1", nothing_listens}, "cannot reach a server at 127.0.0.1:1"},
      {{"load", "--concurrency=0", here}, "--concurrency is 0"},
      {{"sim", "--scene=" + texture_outside, "--frames=2", here}, "outside the scene file's"},
      {{"sim", "--frames=2", misnamed}, "cannot reach a server at nosuchhost.invalid:1"},
      {{"sim", "--channels=3x200", "--frames=2", here}, "--channels channel width is 200"},
      {{"sim", "--channels=" + missing, "--frames=2", here},
       "neither N, NxW, NxWxV nor a readable"},
      {{"sim", "--channels=2x60", "--servers=" + server_->address() + ",127.0.0.1:1", "--frames=2"},
       "cannot reach a server at 127.0.0.1:1"},
      {{"info", nothing_listens}, "cannot reach a server at 127.0.0.1:1"},
      {{"info", misnamed}, "cannot reach a server at nosuchhost.invalid:1"},
      {{"info", here, "--token-file=" + missing}, "--token-file " + missing},
      {{"health", here, "--tls-ca=" + missing}, "--tls-ca " + missing},
      {{"batch", (dir_ / "no-such-job.json").string(), "--servers=127.0.0.1:1", out},
       "no-such-job.json"},
  };
  for (const Case& c : cases) {
    std::vector<std::string> args = {APERTURE_CLIENT_BIN};
    args.insert(args.end(), c.args.begin(), c.args.end());
    SCOPED_TRACE(::testing::PrintToString(c.args));
    const CommandResult result = RunCommand(args, 30);
    EXPECT_EQ(result.exit_code, 2) << result.err;
    EXPECT_THAT(result.err, HasSubstr(c.says));
  }

  // A batch whose servers are all unreachable or misnamed; one that reaches a server renders.
  const std::string job = (dir_ / "job.json").string();
  std::ofstream(job) << R"({"scene": "demo", "size": "16x16", "cameras": ["0,14,420,0,-5,0"]})";
  const CommandResult unreachable =
      RunCommand({APERTURE_CLIENT_BIN, "batch", job, "--servers=127.0.0.1:1,nosuchhost.invalid:1",
                  "-o=" + (dir_ / "frames").string(), "--nocontact_sheet"},
                 30);
  EXPECT_EQ(unreachable.exit_code, 2) << unreachable.err;
  EXPECT_THAT(unreachable.err, HasSubstr("cannot reach a server at 127.0.0.1:1"));
  EXPECT_THAT(unreachable.err, HasSubstr("no server could be reached"));
  const CommandResult one_reached =
      RunCommand({APERTURE_CLIENT_BIN, "batch", job, "--servers=127.0.0.1:1," + server_->address(),
                  "-o=" + (dir_ / "frames").string(), "--nocontact_sheet"},
                 60);
  EXPECT_EQ(one_reached.exit_code, 0) << one_reached.err;
}

TEST_F(ClientTest, HealthExitsZeroWhenServingAndOneWhenNothingListens) {
  std::string error;
  auto own = ServerProcess::Start({}, &error);
  ASSERT_NE(own, nullptr) << error;
  const std::string address = own->address();
  const CommandResult serving =
      RunCommand({APERTURE_CLIENT_BIN, "health", "--server=" + address}, 20);
  EXPECT_EQ(serving.exit_code, 0) << serving.err;
  EXPECT_THAT(serving.out, HasSubstr("SERVING"));

  own.reset();  // killed: nothing listens on that port any more
  const CommandResult down =
      RunCommand({APERTURE_CLIENT_BIN, "health", "--server=" + address, "--deadline_s=2"}, 20);
  EXPECT_EQ(down.exit_code, 1);
  EXPECT_THAT(down.err, HasSubstr("cannot reach a server at " + address));
  // A probe's answer: unreachable or misnamed, the server is not healthy (1, not 2, which
  // Docker's HEALTHCHECK reserves).
  const CommandResult misnamed =
      RunCommand({APERTURE_CLIENT_BIN, "health", "--server=nosuchhost.invalid:1"}, 20);
  EXPECT_EQ(misnamed.exit_code, 1);
  EXPECT_THAT(misnamed.err, HasSubstr("nosuchhost.invalid:1"));
}

TEST_F(ClientTest, LoadReportsThroughputAndLatency) {
  const CommandResult result =
      Client({"load", "--scene=" + WriteGroundScene(dir_), "--camera=0,1.7,0,0,-10,0",
              "--concurrency=2", "--requests=6", "--size=64x48", "--json"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const v1::LoadReport report = ParseReport<v1::LoadReport>(result.out);
  EXPECT_EQ(report.ok(), 6u);
  EXPECT_EQ(report.failed(), 0u);
  EXPECT_EQ(report.concurrency(), 2u);
  EXPECT_GT(report.latency_ms().p99(), 0);
  EXPECT_GE(report.latency_ms().p99(), report.latency_ms().p50());
  EXPECT_GT(report.frames_per_s(), 0);
}

TEST_F(ClientTest, LoadExitsOneWhenRequestsFailed) {
  // 9000 x 9000 is over the server's --max-pixels: every request is refused.
  const CommandResult result = Client(
      {"load", "--scene=demo", "--concurrency=1", "--requests=2", "--size=9000x9000", "--json"});
  EXPECT_EQ(result.exit_code, 1) << result.out << result.err;
  const v1::LoadReport report = ParseReport<v1::LoadReport>(result.out);
  EXPECT_EQ(report.failed(), 2u);
  EXPECT_EQ(report.errors().at("INVALID_ARGUMENT"), 2u);
}

TEST_F(ClientTest, SimStreamsFramesAtARate) {
  const CommandResult result =
      Client({"sim", "--scene=" + WriteGroundScene(dir_), "--camera=0,1.7,0,0,-10,0", "--rate=20",
              "--frames=8", "--size=64x48", "--json"});
  ASSERT_EQ(result.exit_code, 0) << result.out << result.err;
  const v1::SimReport report = ParseReport<v1::SimReport>(result.out);
  EXPECT_EQ(report.frames(), 8u);
  EXPECT_EQ(report.ok(), 8u);
  EXPECT_EQ(report.dropped(), 0u);
  EXPECT_EQ(report.status(), "OK");
  EXPECT_TRUE(report.channels().empty());
}

// The scene's clock runs with the slots (frame i at i / rate seconds): a light flashing on for
// the first half of every second shows in the last frame of two at 4 Hz (0.25 s) and not in the
// last of three (0.5 s).
TEST_F(ClientTest, SimRunsTheScenesClockWithTheSlots) {
  const std::string scene = (dir_ / "flasher.json").string();
  std::ofstream(scene) << R"({"name": "flasher", "sky": {"r": 0, "g": 0, "b": 0},
    "lights": [{"position": {"z": -50}, "intensityCd": 1000,
                "flash": {"periodS": 1, "onS": 0.5}}]})";
  auto light_in_last_frame = [&](int frames) {
    const std::filesystem::path last = dir_ / ("last-" + std::to_string(frames));
    const CommandResult result =
        Client({"sim", "--scene=" + scene, "--camera=0,0,0,0,0,0", "--rate=4",
                "--frames=" + std::to_string(frames), "--size=32x20", "--float_pixels",
                "--last_frames=" + last.string()});
    EXPECT_EQ(result.exit_code, 0) << result.out << result.err;
    int w = 0, h = 0;
    const std::vector<float> pixels = ReadPixels((last / "channel-0.exr").string(), &w, &h);
    double sum = 0;
    for (size_t k = 0; k < pixels.size(); k += 4) sum += pixels[k];
    return sum;
  };
  EXPECT_GT(light_in_last_frame(2), 0.1);
  EXPECT_EQ(light_in_last_frame(3), 0);
}

// Three channels of a JSON-lines path (a camera and an update on its first line): their last
// frames side by side are one wide frame, the one a single camera with the whole frustum and the
// same update renders.
TEST_F(ClientTest, SimChannelsTileOneWideViewAndFlyAJsonPath) {
  const std::string path = (dir_ / "path.jsonl").string();
  std::ofstream(path) << "# a camera behind the aircraft, which turns\n"
                      << R"({"camera": {"position": {"x": 3, "y": 9, "z": 130}, "pitchDeg": -4},)"
                      << R"( "update": {"objects": [{"name": "aircraft", "transform": )"
                      << R"({"translation": {"z": 60}, "yawDeg": 30}}]}})"
                      << "\n"
                      << "\n"
                      << R"({"update": {"sky": {"r": 0.9, "g": 0.5, "b": 0.2}}})"
                      << "\n";
  const std::filesystem::path last = dir_ / "last";
  const CommandResult result =
      Client({"sim", "--scene=demo", "--path=" + path, "--channels=3", "--rate=4", "--frames=5",
              "--size=64x40", "--filter=trilinear", "--float_pixels",
              "--last_frames=" + last.string(), "--json"});
  ASSERT_EQ(result.exit_code, 0) << result.out << result.err;
  const v1::SimReport report = ParseReport<v1::SimReport>(result.out);
  EXPECT_EQ(report.frames(), 2u);  // the path's two frames
  EXPECT_LT(report.worst_channel(), 3u);
  ASSERT_EQ(report.channels_size(), 3);
  for (const v1::SimChannelReport& channel : report.channels()) EXPECT_EQ(channel.frames(), 2u);

  // The same frame from one camera: 3 x 64 pixels wide, its frustum the three channels' union.
  auto stub = v1::Render::NewStub(
      grpc::CreateChannel(server_->address(), grpc::InsecureChannelCredentials()));
  const v1::LoadSceneResponse loaded = LoadBuiltinScene(*stub, "demo");
  ASSERT_FALSE(loaded.scene_id().empty());
  v1::RenderFrameRequest wide;
  wide.set_scene_id(loaded.scene_id());
  v1::Camera& camera = *wide.mutable_camera();
  camera.mutable_position()->set_x(3), camera.mutable_position()->set_y(9);
  camera.mutable_position()->set_z(130), camera.set_pitch_deg(-4);
  camera.set_near(loaded.default_camera().near());
  const double half_height = std::tan(M_PI / 6);            // fov 60
  const double half_width = 3 * half_height * 64.0 / 40.0;  // three channels of 64 x 40
  camera.mutable_frustum()->set_left_deg(-std::atan(half_width) * 180 / M_PI);
  camera.mutable_frustum()->set_right_deg(std::atan(half_width) * 180 / M_PI);
  camera.mutable_frustum()->set_bottom_deg(-30);
  camera.mutable_frustum()->set_top_deg(30);
  wide.mutable_options()->set_width(192);
  wide.mutable_options()->set_height(40);
  wide.mutable_options()->set_filter(v1::TEXTURE_FILTER_TRILINEAR);
  wide.mutable_options()->set_pixel_type(v1::PIXEL_TYPE_FLOAT);
  v1::ObjectUpdate& turn = *wide.mutable_update()->add_objects();
  turn.set_name("aircraft");
  turn.mutable_transform()->mutable_translation()->set_z(60);
  turn.mutable_transform()->set_yaw_deg(30);
  wide.mutable_update()->mutable_sky()->set_r(0.9f);
  wide.mutable_update()->mutable_sky()->set_g(0.5f);
  wide.mutable_update()->mutable_sky()->set_b(0.2f);
  v1::RenderFrameResponse response;
  grpc::ClientContext render_context;
  ASSERT_TRUE(stub->RenderFrame(&render_context, wide, &response).ok());
  const std::string wide_file = (dir_ / "wide.exr").string();
  std::ofstream(wide_file, std::ios::binary) << response.exr();
  int ww = 0, wh = 0;
  const std::vector<float> whole = ReadPixels(wide_file, &ww, &wh);
  ASSERT_EQ(ww, 192);
  double worst = 0, sky_red = 0;
  for (int k = 0; k < 3; ++k) {
    int w = 0, h = 0;
    const std::vector<float> part =
        ReadPixels((last / ("channel-" + std::to_string(k) + ".exr")).string(), &w, &h);
    ASSERT_EQ(w, 64);
    ASSERT_EQ(h, 40);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 4; ++c) {
          const float a = part[(static_cast<size_t>(y) * w + x) * 4 + c];
          const float b = whole[(static_cast<size_t>(y) * ww + k * w + x) * 4 + c];
          worst = std::max(worst, static_cast<double>(std::abs(a - b)));
        }
    sky_red = std::max(sky_red, static_cast<double>(part[0]));
  }
  // The same plane through other pixel origins: equal up to rounding.
  EXPECT_LT(worst, 1e-4);
  EXPECT_GT(sky_red, 0.5);  // the second line's sky (the demo's is 0.5 red, fogged)
}

// The path file docs/SERVICE.md shows: every frame rendered, the fog and the aircraft moving.
TEST_F(ClientTest, SimFliesTheDocumentedExamplePath) {
  const CommandResult result = Client(
      {"sim", "--scene=demo", std::string("--path=") + APERTURE_EXAMPLES_DIR + "/taxi-in-fog.jsonl",
       "--rate=20", "--size=32x20", "--filter=trilinear", "--json"});
  ASSERT_EQ(result.exit_code, 0) << result.out << result.err;
  const v1::SimReport report = ParseReport<v1::SimReport>(result.out);
  EXPECT_EQ(report.frames(), 7u);
  EXPECT_EQ(report.dropped(), 0u);
}

TEST_F(ClientTest, SimPathErrorsNameTheFileAndLine) {
  const std::string path = (dir_ / "bad.jsonl").string();
  std::ofstream(path) << "0,14,420,0,-5,0\n"
                      << R"({"update": {"objects": [{"nmae": "aircraft"}]}})"
                      << "\n";
  const CommandResult result =
      Client({"sim", "--scene=demo", "--path=" + path, "--frames=5", "--size=32x20"});
  EXPECT_EQ(result.exit_code, 2) << result.out << result.err;
  EXPECT_THAT(result.err, HasSubstr("bad.jsonl:2: "));
  EXPECT_THAT(result.err, HasSubstr("nmae"));
}

size_t CountFrames(const std::filesystem::path& dir) {
  size_t n = 0;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(dir, error))
    n += entry.path().extension() == ".exr";
  return n;
}

TEST_F(ClientTest, BatchSurvivesALostServerAndResumes) {
  constexpr int kFrames = 200;
  std::string error;
  auto a = ServerProcess::Start({"--threads=1"}, &error);
  ASSERT_NE(a, nullptr) << error;
  auto b = ServerProcess::Start({"--threads=1"}, &error);
  ASSERT_NE(b, nullptr) << error;
  const std::string job = (dir_ / "job.json").string();
  std::ofstream(job) << R"({"scene": "demo", "size": "64x48", "filter": "trilinear",
      "path": {"from": "0,14,-100,0,-5,0", "to": "0,14,-400,0,-5,0", "frames": )"
                     << kFrames << "}}";
  const std::filesystem::path out = dir_ / "frames";
  const std::vector<std::string> batch = {
      APERTURE_CLIENT_BIN,  "batch",          job, "--servers=" + a->address() + "," + b->address(),
      "-o=" + out.string(), "--concurrency=2"};
  auto run = std::async(std::launch::async, [&] { return RunCommand(batch, 120); });

  // Kill one server half-way through the job.
  const auto start = std::chrono::steady_clock::now();
  while (CountFrames(out) < kFrames / 2 &&
         std::chrono::steady_clock::now() - start < std::chrono::seconds(60))
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  const size_t written_at_kill = CountFrames(out);
  b.reset();  // SIGKILL
  EXPECT_LT(written_at_kill, static_cast<size_t>(kFrames)) << "the batch ended before the kill";

  const CommandResult first = run.get();
  EXPECT_EQ(first.exit_code, 0) << first.out << first.err;
  EXPECT_THAT(first.out, HasSubstr("0 failed"));
  EXPECT_EQ(CountFrames(out), static_cast<size_t>(kFrames));
  for (int i = 0; i < kFrames; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06d.exr", i);
    int w = 0, h = 0;
    EXPECT_FALSE(ReadPixels((out / name).string(), &w, &h).empty()) << name;
    EXPECT_EQ(w, 64) << name;
    EXPECT_EQ(h, 48) << name;
  }

  // A rerun finds every frame written and valid, and renders nothing.
  const CommandResult second = RunCommand(
      {APERTURE_CLIENT_BIN, "batch", job, "--servers=" + a->address(), "-o=" + out.string()}, 60);
  EXPECT_EQ(second.exit_code, 0) << second.err;
  EXPECT_THAT(second.out, HasSubstr("0 rendered, 200 skipped"));
}

// A batch job of `frames` frames of the ground scene (written beside it) along a 50 m path.
std::string WriteGroundJob(const std::filesystem::path& dir, const std::string& name,
                           const std::string& size, int frames) {
  WriteGroundScene(dir);
  const std::string job = (dir / name).string();
  std::ofstream(job) << R"({"scene": "ground.json", "size": ")" << size << R"(",
      "path": {"from": "0,1.7,0,0,-10,0", "to": "0,1.7,-50,0,-10,0", "frames": )"
                     << frames << "}}";
  return job;
}

// A frame the server refuses as such is not retried, and the batch says why.
TEST_F(ClientTest, BatchDoesNotRetryARefusedFrameAndSaysWhy) {
  std::string error;
  auto small = ServerProcess::Start({"--max-pixels=1000"}, &error);
  ASSERT_NE(small, nullptr) << error;
  const std::string job = WriteGroundJob(dir_, "refused.json", "64x48", 3);
  const CommandResult result =
      RunCommand({APERTURE_CLIENT_BIN, "batch", job, "--servers=" + small->address(),
                  "-o=" + (dir_ / "refused").string(), "--nocontact_sheet"},
                 60);
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_THAT(result.out, HasSubstr("0 rendered, 0 skipped (already valid), 3 failed, 0 retries"));
  EXPECT_THAT(result.err, HasSubstr("frame 0 failed after 1 attempt(s): INVALID_ARGUMENT"));
  EXPECT_THAT(result.err, HasSubstr("--max-pixels"));
}

// A batch a person can watch. Its output here is not a terminal, so progress
// comes as plain lines (no carriage returns) with frames/s and the server's tally; at the end a
// contact sheet of thumbnails lies next to the frames.
TEST_F(ClientTest, BatchPrintsPlainProgressAndWritesAContactSheet) {
  constexpr int kFrames = 12;
  const std::string job = WriteGroundJob(dir_, "sheet_job.json", "64x36", kFrames);
  const std::filesystem::path out = dir_ / "sheet_frames";
  const CommandResult r = RunCommand(
      {APERTURE_CLIENT_BIN, "batch", job, "--servers=" + server_->address(), "-o=" + out.string()},
      60);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_EQ(r.err.find('\r'), std::string::npos) << r.err;
  EXPECT_THAT(r.err, HasSubstr("progress: 12/12 frames (12 rendered, 0 skipped, 0 failed)"));
  EXPECT_THAT(r.err, HasSubstr("frames/s"));
  EXPECT_THAT(r.err, HasSubstr(server_->address() + " 12 ok"));
  EXPECT_THAT(r.out, HasSubstr("contact sheet: "));
  // 10 thumbnails 160 wide across, 2 rows of 90 (the frames' 16:9), 4-pixel gaps.
  auto in = OIIO::ImageInput::open((out / "contact_sheet.png").string());
  ASSERT_TRUE(in) << OIIO::geterror();
  EXPECT_EQ(in->spec().width, 10 * (160 + 4) + 4);
  EXPECT_EQ(in->spec().height, 2 * (90 + 4) + 4);
  std::vector<uint8_t> rgb(static_cast<size_t>(in->spec().width) * in->spec().height * 3);
  ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, rgb.data()));
  // Thumbnail 0's centre shows the frame (not the sheet's dark background).
  const size_t centre = (static_cast<size_t>(4 + 45) * in->spec().width + 4 + 80) * 3;
  EXPECT_GT(rgb[centre] + rgb[centre + 1] + rgb[centre + 2], 3 * 40);
  // The 13th cell (row 2, third column) is empty background.
  const size_t empty = (static_cast<size_t>(4 + 94 + 45) * in->spec().width + 4 + 2 * 164 + 80) * 3;
  EXPECT_EQ(rgb[empty], 24);
}

std::string FrameName(int i) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%06d.exr", i);
  return name;
}

// --shard I/N: frame f is rendered by shard f mod N only, under its job-wide number; the shards
// of one job fill one directory; --check reads every frame back and names the missing or corrupt
// ones; a shard rerun renders only what its part lacks. A suite (and ctest entry) of its own, with
// its own server, so ClientTest's time limit is not shared.
class BatchShardTest : public ClientTest {};

TEST_F(BatchShardTest, ShardsSplitAJobAndCheckFindsGaps) {
  constexpr int kFrames = 10, kShards = 3;
  const std::string job = WriteGroundJob(dir_, "job.json", "64x48", kFrames);
  const std::filesystem::path out = dir_ / "frames";
  auto batch = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = {APERTURE_CLIENT_BIN, "batch", job,
                                     "--servers=" + server_->address(), "-o=" + out.string()};
    args.insert(args.end(), extra.begin(), extra.end());
    return RunCommand(args, 60);
  };

  // Shard 1 of 3 alone: frames 1, 4, 7 and nothing else.
  const CommandResult one = batch({"--shard=1/3"});
  ASSERT_EQ(one.exit_code, 0) << one.out << one.err;
  EXPECT_THAT(one.out, HasSubstr("shard 1/3: 3 of 10 frames"));
  EXPECT_THAT(one.out, HasSubstr("3 rendered, 0 skipped"));
  for (int i = 0; i < kFrames; ++i)
    EXPECT_EQ(std::filesystem::exists(out / FrameName(i)), i % kShards == 1) << FrameName(i);

  // The whole job is not there yet: --check names the 7 missing frames and exits 1.
  const CommandResult partial = batch({"--check"});
  EXPECT_EQ(partial.exit_code, 1) << partial.out << partial.err;
  EXPECT_THAT(partial.out, HasSubstr("frame_000000.exr: missing"));
  EXPECT_THAT(partial.out, HasSubstr("3 valid, 7 missing, 0 invalid"));
  // ... but shard 1's part is complete.
  EXPECT_EQ(batch({"--check", "--shard=1/3"}).exit_code, 0);

  // The other shards complete the job, each rendering only its own frames.
  const CommandResult zero = batch({"--shard=0/3"});
  ASSERT_EQ(zero.exit_code, 0) << zero.err;
  EXPECT_THAT(zero.out, HasSubstr("shard 0/3: 4 of 10 frames"));
  EXPECT_THAT(zero.out, HasSubstr("4 rendered, 0 skipped"));
  // (A host name in --servers stands for its IPv4 addresses: localhost is this server again.)
  const std::string address = server_->address();
  const std::string by_name = "localhost" + address.substr(address.rfind(':'));
  const CommandResult two =
      RunCommand({APERTURE_CLIENT_BIN, "batch", job, "--servers=" + by_name + "," + address,
                  "-o=" + out.string(), "--shard=2/3"},
                 60);
  ASSERT_EQ(two.exit_code, 0) << two.err;
  EXPECT_THAT(two.out, HasSubstr("3 rendered, 0 skipped"));
  EXPECT_THAT(two.out, HasSubstr("on 1 servers"));
  EXPECT_EQ(CountFrames(out), static_cast<size_t>(kFrames));
  const CommandResult full = batch({"--check"});
  EXPECT_EQ(full.exit_code, 0) << full.out;
  EXPECT_THAT(full.out, HasSubstr("10 valid, 0 missing, 0 invalid"));

  // The whole job run as one batch now finds every frame rendered by the shards, pixel for pixel
  // the frames it would have rendered itself.
  const std::filesystem::path whole = dir_ / "whole";
  const CommandResult reference =
      RunCommand({APERTURE_CLIENT_BIN, "batch", job, "--servers=" + server_->address(),
                  "-o=" + whole.string()},
                 60);
  ASSERT_EQ(reference.exit_code, 0) << reference.err;
  for (int i = 0; i < kFrames; ++i) {
    int w = 0, h = 0;
    EXPECT_TRUE(ReadPixels((out / FrameName(i)).string(), &w, &h) ==
                ReadPixels((whole / FrameName(i)).string(), &w, &h))
        << FrameName(i);
  }

  // Frame 4 deleted, frame 7 cut short (its header still opens): --check names both; a rerun of
  // shard 1 renders exactly those two; shard 0 finds its part complete.
  std::filesystem::remove(out / FrameName(4));
  std::filesystem::resize_file(out / FrameName(7),
                               std::filesystem::file_size(out / FrameName(7)) / 2);
  const CommandResult gaps = batch({"--check"});
  EXPECT_EQ(gaps.exit_code, 1);
  EXPECT_THAT(gaps.out, HasSubstr("frame_000004.exr: missing"));
  EXPECT_THAT(gaps.out, HasSubstr("frame_000007.exr: pixels do not read back"));
  EXPECT_THAT(gaps.out, HasSubstr("8 valid, 1 missing, 1 invalid"));
  const CommandResult rerun = batch({"--shard=1/3"});
  ASSERT_EQ(rerun.exit_code, 0) << rerun.err;
  EXPECT_THAT(rerun.out, HasSubstr("2 rendered, 1 skipped"));
  EXPECT_THAT(batch({"--shard=0/3"}).out, HasSubstr("0 rendered, 4 skipped"));
  EXPECT_EQ(batch({"--check"}).exit_code, 0);

  // A shard outside 0 <= I < N is bad input.
  for (const char* bad : {"--shard=3/3", "--shard=1/0", "--shard=x", "--shard=-1/2"}) {
    const CommandResult result = batch({bad});
    EXPECT_EQ(result.exit_code, 2) << bad;
    EXPECT_THAT(result.err, HasSubstr("must be I/N")) << bad;
  }
}

}  // namespace
}  // namespace aperture::testing
