// aperture-render as a user runs it: a real process, real files.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "support/run_process.h"

namespace {

using Result = aperture::testing::ProcessResult;

Result RunRender(const std::string& args) {
  return aperture::testing::RunProcess(std::string(APERTURE_RENDER_BIN) + " " + args);
}

class RenderCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("aperture_cli_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }
  std::string WriteScene(const std::string& name, const std::string& json) const {
    std::ofstream(Path(name)) << json;
    return Path(name);
  }
  std::filesystem::path dir_;
};

TEST_F(RenderCli, RendersTheDemoToAnExrAndAPreview) {
  const Result r =
      RunRender("--scene demo --size 160x90 --filter trilinear -o " + Path("demo.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("setup"), std::string::npos);
  EXPECT_NE(r.output.find("raster"), std::string::npos);
  EXPECT_NE(r.output.find("encode"), std::string::npos);
  auto in = OIIO::ImageInput::open(Path("demo.exr"));
  ASSERT_TRUE(in);
  EXPECT_EQ(in->spec().width, 160);
  EXPECT_EQ(in->spec().height, 90);
  EXPECT_EQ(in->spec().nchannels, 4);
  EXPECT_EQ(in->spec().format, OIIO::TypeDesc::HALF);
  EXPECT_EQ(in->spec().get_string_attribute("aperture:scene"), "demo-airfield");
  EXPECT_TRUE(std::filesystem::exists(Path("demo.png")));
}

// A one-frame job maps the tables an earlier process built into the machine's store
// instead of building them again; --store none builds in the process and leaves no store.
TEST_F(RenderCli, SecondProcessMapsTheStoreInsteadOfBuilding) {
  const std::string store = Path("store");
  const std::string common = "--scene demo --size 64x36 --nopreview --store " + store + " -o ";
  const Result first = RunRender(common + Path("a.exr"));
  ASSERT_EQ(first.exit_code, 0) << first.output;
  EXPECT_NE(first.output.find("0 entries mapped, 3 built here"), std::string::npos) << first.output;
  const Result second = RunRender(common + Path("b.exr"));
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_NE(second.output.find("3 entries mapped, 0 built here"), std::string::npos)
      << second.output;
  // The same frame either way, and without a store too.
  const Result none =
      RunRender("--scene demo --size 64x36 --nopreview --store none -o " + Path("c.exr"));
  ASSERT_EQ(none.exit_code, 0) << none.output;
  EXPECT_EQ(none.output.find("entries mapped"), std::string::npos) << none.output;
  std::vector<float> pixels[3];
  int k = 0;
  for (const char* name : {"a.exr", "b.exr", "c.exr"}) {
    auto in = OIIO::ImageInput::open(Path(name));
    ASSERT_TRUE(in) << name;
    pixels[k].resize(64 * 36 * 4);
    ASSERT_TRUE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::FLOAT, pixels[k].data()));
    ++k;
  }
  EXPECT_EQ(pixels[0], pixels[1]);
  EXPECT_EQ(pixels[0], pixels[2]);
  // A store directory that cannot be made is a warning, not a failure.
  const Result unusable = RunRender(
      "--scene demo --size 16x9 --filter trilinear --nopreview "
      "--store /proc/no-such-store -o " +
      Path("d.exr"));
  EXPECT_EQ(unusable.exit_code, 0) << unusable.output;
  EXPECT_NE(unusable.output.find("warning: store /proc/no-such-store not used"), std::string::npos)
      << unusable.output;
}

TEST_F(RenderCli, FloatPixelsAndCompressionAreHonoured) {
  const Result r = RunRender(
      "--size 32x24 --filter bilinear --float_pixels --compression piz "
      "--nopreview -o " +
      Path("f.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  auto in = OIIO::ImageInput::open(Path("f.exr"));
  ASSERT_TRUE(in);
  EXPECT_EQ(in->spec().format, OIIO::TypeDesc::FLOAT);
  EXPECT_EQ(in->spec().get_string_attribute("compression"), "piz");
  EXPECT_FALSE(std::filesystem::exists(Path("f.png")));
}

struct BadRun {
  std::string args;
  const char* message;
};

TEST_F(RenderCli, BadInputExitsNonZeroNamingTheProblem) {
  const std::string quad_tail =
      R"(, {"x": 1, "y": 0, "z": -5}, {"x": 1, "y": 1, "z": -5}, {"x": 0, "y": 1, "z": -5}]}]}]})";
  const std::string head = R"({"meshes": [{"id": "m", "polygons": [{"vertices": [)";
  const std::vector<BadRun> runs = {
      {"--size 0x10", "options.width is 0"},
      {"--size 16385x10", "must be 1..16384"},
      {"--size big", "WIDTHxHEIGHT"},
      {"--aa box3", "--aa 'box3' is not one of box1, box2, tent2"},
      {"--filter sharp", "--filter 'sharp' is not one of"},
      {"--camera 1,2,3", "X,Y,Z,YAW,PITCH,ROLL"},
      {"--camera nan,1,2,0,0,0", "camera position is not finite"},
      {"--mode pathtrace", "--mode 'pathtrace' is not one of raster, raytrace, both"},
      {"--region 0,0,4000x10", "region: 4000x10 at (0, 0) is empty or not inside"},
      {"--fov -5", "field of view"},
      {"--compression lzw", "--compression 'lzw' is not one of"},
      {"--scene " + Path("missing.json"), "cannot open scene file"},
      {"--scene " + WriteScene("syntax.json", "{\"meshes\": ["), "scene JSON is invalid"},
      {"--scene " + WriteScene("unknown.json", R"({"meshs": []})"), "meshs"},
      {"--scene " + WriteScene("nan.json", head + R"({"x": "NaN", "y": 0, "z": -5})" + quad_tail),
       "vertices[0]"},
      {"--scene " + WriteScene("two.json", head + R"({"x": 0}, {"x": 1}]}]}]})"),
       "needs at least 3"},
      {"--scene " + WriteScene("degenerate.json", head + R"({"x": 0}, {"x": 1}, {"x": 2}]}]}]})"),
       "degenerate"},
      {"--scene " +
           WriteScene("texture.json", R"({"textures": [{"id": "t", "file": "gone.png"}]})"),
       "gone.png"},
  };
  for (const BadRun& run : runs) {
    const Result r = RunRender(run.args + " --nopreview -o " + Path("bad.exr"));
    EXPECT_NE(r.exit_code, 0) << run.args;
    EXPECT_NE(r.output.find(run.message), std::string::npos) << run.args << "\n" << r.output;
    EXPECT_EQ(r.output.find("Aborted"), std::string::npos) << run.args;
  }
  EXPECT_FALSE(std::filesystem::exists(Path("bad.exr")));
}

// Spheres and cylinders are drawn by the raytrace mode; the raster mode stops naming it.
TEST_F(RenderCli, SpheresRenderInRaytraceModeAndRasterNamesIt) {
  const std::string scene = WriteScene("sphere.json", R"({"spheres": [{"center": {"z": -4},
      "radius": 1}], "cylinders": [{"base": {"x": 2, "z": -6}, "top": {"x": 2, "y": 1, "z": -6},
      "radius": 0.5, "capped": true}]})");
  Result r = RunRender("--scene " + scene + " --camera 0,0,0,0,0,0 --size 40x30 --mode raytrace " +
                       "--nopreview -o " + Path("rt.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("corner rays"), std::string::npos) << r.output;
  EXPECT_TRUE(std::filesystem::exists(Path("rt.exr")));
  r = RunRender("--scene " + scene + " --camera 0,0,0,0,0,0 --size 40x30 --nopreview -o " +
                Path("raster.exr"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("2 sphere(s)/cylinder(s)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("--mode raytrace"), std::string::npos) << r.output;
  r = RunRender("--scene " + WriteScene("bad.json", R"({"spheres": [{"radius": -1}]})") +
                " --mode raytrace --nopreview -o " + Path("bad.exr"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("spheres[0].radius: must be > 0, is -1"), std::string::npos) << r.output;
}

// --zip_level: 1..9 reach the file (a faster level, a larger file); anything else is a usage error
// naming the flag, and nothing is written.
TEST_F(RenderCli, ZipLevelIsValidatedAndApplied) {
  const std::string common = "--size 160x120 --nopreview --threads 2 -o ";
  Result fast = RunRender("--zip_level 1 " + common + Path("z1.exr"));
  Result small = RunRender("--zip_level 9 " + common + Path("z9.exr"));
  ASSERT_EQ(fast.exit_code, 0) << fast.output;
  ASSERT_EQ(small.exit_code, 0) << small.output;
  EXPECT_GT(std::filesystem::file_size(Path("z1.exr")), std::filesystem::file_size(Path("z9.exr")));
  const Result bad = RunRender("--zip_level 12 " + common + Path("z12.exr"));
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("zip_level 12 is outside 1..9"), std::string::npos) << bad.output;
  EXPECT_FALSE(std::filesystem::exists(Path("z12.exr")));
}

// --mode both: the raster frame, then the raytraced one next to it, timed in one run.
TEST_F(RenderCli, ModeBothRendersRasterThenRaytrace) {
  const Result r = RunRender(
      "--scene demo --size 64x36 --filter trilinear --mode both --threads 2 "
      "--nopreview -o " +
      Path("demo.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(Path("demo.exr")));
  EXPECT_TRUE(std::filesystem::exists(Path("demo-raytrace.exr")));
  EXPECT_NE(r.output.find("M rays/s"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("raytrace takes"), std::string::npos) << r.output;
}

}  // namespace
