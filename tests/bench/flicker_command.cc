// aperture-bench flicker: how much each filter shimmers. A slow fly-over
// of the grazing plane (DESIGN.md's benchmark plane), turning as it goes; per frame, the mean
// absolute change from the previous frame, compared with the same figure of the converged
// reference sequence. What a filter changes beyond what the reference changes is flicker: aliasing
// that moves with the camera, or a choice of copies that jumps from frame to frame.
#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "base/stopwatch.h"
#include "bench/bench_commands.h"
#include "bench/bench_inputs.h"
#include "testing/grazing_plane.h"
#include "texture/aniso_sampler.h"
#include "texture/mip_pyramid.h"
#include "texture/oiio_sampler.h"
#include "texture/prefiltered_table_builder.h"
#include "tools/tex_args.h"

namespace aperture::bench {
namespace {

struct Track {
  const char* name;
  const TextureSampler* sampler;  // null: the reference
  Image previous;
  double psnr = 0, change = 0, excess = 0;
};

int RunFlicker(int argc, char** argv) {
  auto args =
      ParseArgs(argc, argv,
                {"--texture", "--data", "--frames", "--pitch", "--turn", "--speed", "--size",
                 "--aperture", "--ref-min", "--ref-density", "--ref-max", "--out", "--threads"});
  if (!args.ok()) return Fail("flicker", std::string(args.status().message()));
  if (args->help || !args->positional.empty()) {
    std::fprintf(
        args->help ? stdout : stderr,
        "usage: aperture-bench flicker [--texture checker|NAME] [--data DIR] [--frames 120]\n"
        "         [--pitch 3] [--turn 30] [--speed 0.05] [--size 320x240] [--aperture 1]\n"
        "         [--ref-min 8] [--ref-density 4] [--ref-max 64] [--out DIR] [--threads N]\n"
        "A slow fly-over of the grazing plane at --pitch degrees, turning --turn degrees over\n"
        "--frames frames and moving --speed world units a frame (the texture repeats every 4).\n"
        "For trilinear, aniso (seed 000), oiio (OpenImageIO's TextureSystem, its defaults) and\n"
        "oiio16 (OpenImageIO, anisotropic 16, bilinear) against the supersampled reference of\n"
        "each frame: PSNR, the mean absolute change from the previous frame, its ratio to the\n"
        "reference's own change, and the excess flicker (the mean of |change - the reference's\n"
        "change|). Per-frame figures go to DIR/flicker.csv.\n");
    return args->help ? 0 : 2;
  }
  int frames = 0, ref_min = 0, ref_max = 0, threads = 0;
  double pitch = 0, turn = 0, speed = 0, aperture = 0, density = 0;
  uint32_t width = 0, height = 0;
  const std::string size = args->Get("--size", "320x240");
  const size_t x = size.find('x');
  if (!absl::SimpleAtoi(args->Get("--frames", "120"), &frames) || frames < 2 ||
      !absl::SimpleAtod(args->Get("--pitch", "3"), &pitch) || !(pitch > 0 && pitch < 90) ||
      !absl::SimpleAtod(args->Get("--turn", "30"), &turn) || !std::isfinite(turn) ||
      !absl::SimpleAtod(args->Get("--speed", "0.05"), &speed) || !std::isfinite(speed) ||
      !absl::SimpleAtod(args->Get("--aperture", "1"), &aperture) ||
      !(aperture > 0 && aperture <= 16) ||
      !absl::SimpleAtoi(args->Get("--ref-min", "8"), &ref_min) || ref_min < 1 ||
      !absl::SimpleAtod(args->Get("--ref-density", "4"), &density) || !(density > 0) ||
      !absl::SimpleAtoi(args->Get("--ref-max", "64"), &ref_max) || ref_max < 2 ||
      !absl::SimpleAtoi(args->Get("--threads", "0"), &threads) || threads < 0 ||
      x == std::string::npos || !absl::SimpleAtoi(size.substr(0, x), &width) ||
      !absl::SimpleAtoi(size.substr(x + 1), &height) || width < 2 || height < 2 || width > 4096 ||
      height > 4096)
    return Fail("flicker",
                "--frames >= 2, --pitch in (0, 90), --aperture in (0, 16], --size WxH (2..4096), "
                "--ref-min >= 1, --ref-max >= 2, --ref-density > 0, --threads >= 0");
  std::unique_ptr<tbb::global_control> limit;
  if (threads > 0)
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                  threads);
  auto textures = LoadBenchTextures(args->Get("--texture", "checker"),
                                    args->Get("--data", "../shared/data/raster"));
  if (!textures.ok()) return Fail("flicker", std::string(textures.status().message()));
  const BenchTexture& tex = textures->front();
  auto block = BuildPrefilteredTable(tex.image);
  if (!block.ok()) return Fail("flicker", std::string(block.status().message()));
  auto table = block->View();
  if (!table.ok()) return Fail("flicker", std::string(table.status().message()));
  MipPyramid pyramid(tex.image);
  TrilinearSampler trilinear(pyramid);
  AnisoSampler aniso(*table);
  auto oiio = OiioSampler::Create(tex.image);
  if (!oiio.ok()) return Fail("flicker", std::string(oiio.status().message()));
  auto oiio16 = OiioSampler::Create(tex.image, "", kOiioAniso16Bilinear);
  if (!oiio16.ok()) return Fail("flicker", std::string(oiio16.status().message()));

  const std::string out_dir = args->Get("--out", "out/bench-flicker");
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  std::ofstream csv(out_dir + "/flicker.csv");
  if (ec || !csv) return Fail("flicker", absl::StrCat("cannot write ", out_dir, "/flicker.csv"));
  csv << "frame,yaw,mode,psnr,change,reference_change,excess\n";

  Track tracks[] = {{"reference", nullptr, {}},
                    {"trilinear", &trilinear, {}},
                    {"aniso", &aniso, {}},
                    {"oiio", oiio->get(), {}},
                    {"oiio16", oiio16->get(), {}}};
  GrazingPlaneView view;
  view.width = static_cast<int>(width);
  view.height = static_cast<int>(height);
  view.pitch_deg = pitch;
  view.aperture = aperture;
  const int first = FirstMeasuredRow(view);
  const Stopwatch timer;
  for (int t = 0; t < frames; ++t) {
    view.yaw_deg = turn * t / (frames - 1);
    const Image ref = RenderGroundReference(view, tex.image, density, ref_max, ref_min);
    Track& reference = tracks[0];
    const double ref_change =
        t > 0 ? MeanAbsoluteChange(ref, reference.previous, nullptr, nullptr, first) : 0;
    for (Track& track : tracks) {
      Image image = track.sampler ? RenderGroundImage(view, *track.sampler) : ref;
      if (t > 0) {
        const double change =
            track.sampler ? MeanAbsoluteChange(image, track.previous, nullptr, nullptr, first)
                          : ref_change;
        const double excess = track.sampler ? MeanAbsoluteChange(image, track.previous, &ref,
                                                                 &reference.previous, first)
                                            : 0;
        const double psnr = Psnr(image, ref, first);
        track.change += change / (frames - 1);
        track.excess += excess / (frames - 1);
        if (track.sampler) track.psnr += psnr / (frames - 1);
        csv << t << "," << view.yaw_deg << "," << track.name << "," << psnr << "," << change << ","
            << ref_change << "," << excess << "\n";
      }
      if (&track != &reference) track.previous = std::move(image);
    }
    reference.previous = ref;
    MoveForward(&view, speed);
    if ((t + 1) % 10 == 0 || t + 1 == frames)
      std::fprintf(stderr, "  frame %d of %d (%.0f s)\n", t + 1, frames, timer.Seconds());
  }
  std::printf(
      "%s, %dx%d, pitch %g, turning %g degrees over %d frames, %g world units a frame, a = %g; "
      "reference %d..%d strata a side, %g per texel\n\n"
      "| mode | mean PSNR | frame-to-frame change | / reference's | excess flicker |\n"
      "|---|---:|---:|---:|---:|\n",
      tex.name.c_str(), width, height, pitch, turn, frames, speed, aperture, ref_min, ref_max,
      density);
  const double ref_change = tracks[0].change;
  for (const Track& track : tracks) {
    if (!track.sampler) {
      std::printf("| reference | - | %.5f | 1.00 | - |\n", track.change);
      continue;
    }
    std::printf("| %s | %.2f | %.5f | %.2f | %.5f |\n", track.name, track.psnr, track.change,
                ref_change > 0 ? track.change / ref_change : 0.0, track.excess);
  }
  return 0;
}

}  // namespace

std::vector<BenchCommand> FlickerCommands() {
  return {{"flicker",
           "temporal stability: a slow turning fly-over, each filter's frame-to-frame change "
           "against the reference's",
           RunFlicker}};
}

}  // namespace aperture::bench
