// aperture-bench filter: the grazing-plane benchmark (DESIGN.md) of every texture filter against
// a supersampled reference, from several directions and positions, with per-row plots.
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "base/stopwatch.h"
#include "bench/bench_commands.h"
#include "bench/bench_inputs.h"
#include "bench/row_plot.h"
#include "io/exr_writer.h"
#include "testing/grazing_plane.h"
#include "texture/aniso_sampler.h"
#include "texture/mip_pyramid.h"
#include "texture/oiio_sampler.h"
#include "texture/prefiltered_table.h"
#include "texture/prefiltered_table_builder.h"
#include "tools/tex_args.h"

namespace aperture::bench {
namespace {

// The modes compared: trilinear, aniso, and OpenImageIO's TextureSystem as the peer (its
// defaults, and anisotropic 16 with bilinear texels).
constexpr int kModes = 4;

int RunFilter(int argc, char** argv) {
  auto args = ParseArgs(argc, argv,
                        {"--textures", "--data", "--angles", "--apertures", "--out", "--cache",
                         "--ref-density", "--ref-max", "--ref-min", "--timing-rows", "--threads",
                         "--yaws", "--positions", "--aniso-options"});
  if (!args.ok()) return Fail("filter", std::string(args.status().message()));
  if (args->help || !args->positional.empty()) {
    std::fprintf(
        args->help ? stdout : stderr,
        "usage: aperture-bench filter [--textures checker,NAME...] [--data DIR]\n"
        "         [--angles 5,20,60] [--yaws 0] [--apertures 2,1] [--out DIR] [--cache DIR]\n"
        "         [--ref-density D] [--ref-max K] [--ref-min K] [--timing-rows S] [--threads N]\n"
        "         [--positions P] [--aniso-options NAME=VALUE,...]\n"
        "The grazing-plane benchmark (DESIGN.md): PSNR of trilinear, aniso, oiio (OpenImageIO's\n"
        "defaults) and oiio16 (OpenImageIO, anisotropic 16, bilinear) against the supersampled\n"
        "reference of the same aperture, and ns per sample single-threaded; then PSNR by band\n"
        "of footprint length and by the footprint's angle from the nearest texture axis\n"
        "(5-degree bins), and with several --yaws the spread of each mode's PSNR across them\n"
        "(aniso's is meant to stay under 0.8 dB).\n"
        "--yaws turns the camera about the vertical (0: along the texture's v axis); the\n"
        "reference takes D strata per texel of extent per side, at least --ref-min (2) and at\n"
        "most --ref-max (128).\n"
        "--positions P (default 1) scores each view from P camera positions over the plane and\n"
        "pools their squared errors: looking along a texture axis every pixel row meets the\n"
        "texels and the checkerboard's edges at one phase, so one position scores one phase\n"
        "(compare yaws with P >= 4). Each position has its own reference; the plots pool\n"
        "the positions too, the images and timings are the first position's.\n"
        "Writes every image as EXR under --out (default out/bench-filter), and per view a plot\n"
        "of PSNR by row (_rows.png: trilinear blue, aniso red, oiio green, oiio16 grey; grid\n"
        "every 10 dB, rows from the first measured one, left, to the bottom); references are\n"
        "cached under --cache (default: the cache folder in --out).\n"
        "--aniso-options sets fields of the aniso sampler's AnisoOptions over their defaults\n"
        "(texture/aniso/aniso_options.h, docs/ANISO.md), e.g. box_probes=false or\n"
        "box_probe_thickness=1.5,box_probe_fade=4: an experiment on a regime.\n");
    return args->help ? 0 : 2;
  }
  const std::string out_dir = args->Get("--out", "out/bench-filter");
  const std::string cache_dir = args->Get("--cache", out_dir + "/cache");
  auto angles = ParseNumbers(args->Get("--angles", "5,20,60"), "--angles");
  auto apertures = ParseNumbers(args->Get("--apertures", "2,1"), "--apertures");
  auto density = ParseNumbers(args->Get("--ref-density", "2"), "--ref-density");
  auto yaws = ParseNumbers(args->Get("--yaws", "0"), "--yaws");
  int ref_max = 0, ref_min = 0, timing_rows = 0, threads = 0, positions = 0;
  if (!angles.ok() || !apertures.ok() || !density.ok() || !yaws.ok())
    return Fail("filter", "--angles, --yaws, --apertures and --ref-density take numbers");
  if (!absl::SimpleAtoi(args->Get("--ref-max", "128"), &ref_max) || ref_max < 2 ||
      !absl::SimpleAtoi(args->Get("--ref-min", "2"), &ref_min) || ref_min < 1 ||
      !absl::SimpleAtoi(args->Get("--timing-rows", "4"), &timing_rows) || timing_rows < 1 ||
      !absl::SimpleAtoi(args->Get("--threads", "0"), &threads) || threads < 0 ||
      !absl::SimpleAtoi(args->Get("--positions", "1"), &positions) || positions < 1 ||
      positions > 64)
    return Fail("filter",
                "--ref-max >= 2, --ref-min >= 1, --timing-rows >= 1, --threads >= 0, "
                "--positions 1..64");
  for (double a : *apertures)
    if (a <= 0 || a > 16) return Fail("filter", "apertures must be in (0, 16]");
  for (double t : *angles)
    if (t <= 0 || t >= 90) return Fail("filter", "angles must be in (0, 90) degrees");
  const auto aniso_options = AnisoOptions::Parse(args->Get("--aniso-options", ""));
  if (!aniso_options.ok()) return Fail("filter", std::string(aniso_options.status().message()));
  if (const std::string changed = aniso_options->ChangedFields(); !changed.empty())
    std::fprintf(stderr, "aniso options: %s (the rest at their defaults)\n", changed.c_str());
  std::unique_ptr<tbb::global_control> limit;
  if (threads > 0)
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                  threads);
  auto textures = LoadBenchTextures(args->Get("--textures", "checker,asphalt_torcs_1024"),
                                    args->Get("--data", "../shared/data/raster"));
  if (!textures.ok()) return Fail("filter", std::string(textures.status().message()));
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (!ec) std::filesystem::create_directories(cache_dir, ec);
  if (ec) return Fail("filter", absl::StrCat("cannot create ", cache_dir));

  std::printf(
      "| texture | theta | yaw | a | rows | trilinear dB | aniso dB | oiio dB | oiio16 dB | "
      "aniso - best oiio | aniso - trilinear | trilinear ns | aniso ns | oiio ns | oiio16 ns | "
      "oiio / aniso |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  std::fflush(stdout);
  // PSNR by band of footprint length (texels a pixel step spans), printed after the table.
  const std::vector<double> kBandEdges = {2, 4, 16};
  std::vector<std::string> band_rows;
  // And by the footprint's long axis's angle from the nearest texture axis, 5-degree bins.
  const std::vector<double> kAngleEdges = {5, 10, 15, 20, 25, 30, 35, 40};
  std::vector<std::string> angle_rows;
  // And the spread of each mode's view PSNR across the yaws, per texture, aperture and pitch.
  std::vector<std::string> spread_rows;
  for (const BenchTexture& tex : *textures) {
    const Stopwatch build_timer;
    auto block = BuildPrefilteredTable(tex.image);
    if (!block.ok()) return Fail("filter", std::string(block.status().message()));
    const double build_s = build_timer.Seconds();
    auto table = block->View();
    if (!table.ok()) return Fail("filter", std::string(table.status().message()));
    MipPyramid pyramid(tex.image);
    TrilinearSampler trilinear(pyramid);
    AnisoSampler aniso(*table, *aniso_options);
    auto oiio = OiioSampler::Create(tex.image);
    if (!oiio.ok()) return Fail("filter", std::string(oiio.status().message()));
    auto oiio16 = OiioSampler::Create(tex.image, "", kOiioAniso16Bilinear);
    if (!oiio16.ok()) return Fail("filter", std::string(oiio16.status().message()));
    std::fprintf(stderr, "%s: %dx%d, table %zu bytes built in %.2f s\n", tex.name.c_str(),
                 tex.image.width(), tex.image.height(), block->bytes.size(), build_s);
    for (double a : *apertures) {
      for (double theta : *angles) {
        std::vector<double> view_psnr[kModes];  // per mode, one per yaw
        for (double yaw : *yaws) {
          GrazingPlaneView view;
          view.pitch_deg = theta;
          view.yaw_deg = yaw;
          view.aperture = a;
          const int first = FirstMeasuredRow(view);
          const std::string stem =
              absl::StrCat(out_dir, "/", tex.name, "_p", theta, "_y", yaw, "_a", a);
          struct Mode {
            const char* name;
            const TextureSampler* sampler;
            double ns = 0;
            // Per position: the PSNR, by band, by angle and by row.
            std::vector<double> psnr;
            std::vector<std::vector<double>> bands, angles, rows;
          };
          Mode modes[kModes] = {{"trilinear", &trilinear},
                                {"aniso", &aniso},
                                {"oiio", oiio->get()},
                                {"oiio16", oiio16->get()}};
          std::vector<uint64_t> pixels;  // per band; the same at every position
          std::vector<uint64_t> angle_pixels;
          for (int k = 0; k < positions; ++k) {
            const GrazingPlaneView at = ViewAtPosition(view, k);
            const Stopwatch ref_timer;
            bool cached = false;
            auto ref =
                CachedReference(at, tex, density->front(), ref_max, ref_min, cache_dir, &cached);
            if (!ref.ok()) return Fail("filter", std::string(ref.status().message()));
            std::fprintf(stderr, "  theta %g yaw %g a %g position %d/%d: reference %s in %.1f s\n",
                         theta, yaw, a, k + 1, positions, cached ? "from cache" : "computed",
                         ref_timer.Seconds());
            for (Mode& m : modes) {
              const Image img = RenderGroundImage(at, *m.sampler);
              m.psnr.push_back(Psnr(img, *ref, first));
              m.rows.push_back(PsnrByRow(img, *ref, first));
              m.bands.push_back(PsnrByFootprintBand(img, *ref, at, tex.image.width(), first,
                                                    kBandEdges, &pixels));
              m.angles.push_back(PsnrByBand(
                  img, *ref, first, [&](int i, int j) { return FootprintAngleFromAxis(at, i, j); },
                  kAngleEdges, &angle_pixels));
              if (k > 0) continue;
              m.ns = NanosecondsPerSample(at, *m.sampler, timing_rows);
              if (auto s = WriteExrFile(img, {}, absl::StrCat(stem, "_", m.name, ".exr")); !s.ok())
                return Fail("filter", std::string(s.message()));
            }
            if (k == 0)
              if (auto s = WriteExrFile(*ref, {}, absl::StrCat(stem, "_reference.exr")); !s.ok())
                return Fail("filter", std::string(s.message()));
            if (positions > 1)
              std::fprintf(stderr, "    trilinear %.2f aniso %.2f oiio %.2f oiio16 %.2f dB\n",
                           modes[0].psnr.back(), modes[1].psnr.back(), modes[2].psnr.back(),
                           modes[3].psnr.back());
          }
          // Pooled over the positions: the PSNR of the mean squared error.
          auto pooled = [](const std::vector<std::vector<double>>& per_position, size_t i) {
            std::vector<double> values;
            for (const std::vector<double>& p : per_position) values.push_back(p[i]);
            return std::isnan(values.front()) ? NAN : PooledPsnr(values);
          };
          std::string band_row = absl::StrCat("| ", tex.name, " | ", theta, " | ", yaw, " | ", a);
          std::string angle_row = band_row;
          for (int m : {1, 2, 3})  // aniso, oiio, oiio16
            for (size_t b = 0; b < angle_pixels.size(); ++b)
              absl::StrAppend(
                  &angle_row, " | ",
                  angle_pixels[b] == 0 ? "-" : absl::StrFormat("%.2f", pooled(modes[m].angles, b)));
          // Per-row PSNR, one line per mode: trilinear blue, aniso red, oiio green, oiio16
          // grey.
          const Rgba kColours[kModes] = {{0.1f, 0.2f, 0.9f, 1},
                                         {0.9f, 0.1f, 0.1f, 1},
                                         {0.1f, 0.6f, 0.1f, 1},
                                         {0.5f, 0.5f, 0.5f, 1}};
          std::vector<PlotSeries> rows;
          double psnr[kModes];
          for (int m = 0; m < kModes; ++m) {
            psnr[m] = PooledPsnr(modes[m].psnr);
            for (size_t b = 0; b < pixels.size(); ++b)
              absl::StrAppend(
                  &band_row, " | ",
                  pixels[b] == 0 ? "-" : absl::StrFormat("%.2f", pooled(modes[m].bands, b)));
            std::vector<double> by_row(view.height);
            for (int j = 0; j < view.height; ++j) by_row[j] = pooled(modes[m].rows, j);
            rows.push_back({std::move(by_row), kColours[m]});
          }
          if (auto s =
                  WritePngPreview(PlotRows(rows, first, 800, 300), absl::StrCat(stem, "_rows.png"));
              !s.ok())
            return Fail("filter", std::string(s.message()));
          std::printf(
              "| %s | %g | %g | %g | %d-%d | %.2f | %.2f | %.2f | %.2f | %+.2f | %+.2f | %.0f | "
              "%.0f | %.0f | %.0f | %.1fx |\n",
              tex.name.c_str(), theta, yaw, a, first, view.height - 1, psnr[0], psnr[1], psnr[2],
              psnr[3], psnr[1] - std::max(psnr[2], psnr[3]), psnr[1] - psnr[0], modes[0].ns,
              modes[1].ns, modes[2].ns, modes[3].ns, modes[2].ns / modes[1].ns);
          std::fflush(stdout);
          band_rows.push_back(band_row + " |");
          angle_rows.push_back(angle_row + " |");
          for (int m = 0; m < kModes; ++m) view_psnr[m].push_back(psnr[m]);
        }
        std::string spread_row = absl::StrCat("| ", tex.name, " | ", theta, " | ", a);
        for (int m = 0; m < kModes; ++m) {
          const YawSpread s = SpreadAcrossYaws(*yaws, view_psnr[m]);
          absl::StrAppend(&spread_row, absl::StrFormat(" | %.2f (%g)", s.spread, s.lowest_yaw));
        }
        spread_rows.push_back(spread_row + " |");
      }
    }
  }
  std::printf(
      "\nPSNR by footprint length (texels a pixel step spans), trilinear / aniso / oiio / "
      "oiio16:\n\n"
      "| texture | theta | yaw | a | tri < 2 | tri 2-4 | tri 4-16 | tri >= 16 | aniso < 2 | "
      "aniso 2-4 | aniso 4-16 | aniso >= 16 | oiio < 2 | oiio 2-4 | oiio 4-16 | oiio >= 16 | "
      "oiio16 < 2 | oiio16 2-4 | oiio16 4-16 | oiio16 >= 16 |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const std::string& row : band_rows) std::printf("%s\n", row.c_str());
  std::printf(
      "\nPSNR by the footprint's long axis's angle from the nearest texture axis (degrees), aniso "
      "/ oiio / oiio16:\n\n| texture | theta | yaw | a");
  const size_t angle_bins = kAngleEdges.size() + 1;  // the last runs to 45 degrees
  for (const char* mode : {"aniso", "oiio", "oiio16"})
    for (size_t b = 0; b < angle_bins; ++b)
      std::printf(" | %s %g-%g", mode, b == 0 ? 0.0 : kAngleEdges[b - 1],
                  b + 1 < angle_bins ? kAngleEdges[b] : 45.0);
  std::printf(" |\n|---|---|---|---");
  for (size_t b = 0; b < 3 * angle_bins; ++b) std::printf("|---");
  std::printf("|\n");
  for (const std::string& row : angle_rows) std::printf("%s\n", row.c_str());
  if (yaws->size() > 1) {
    std::printf(
        "\nSpread of the view PSNR across the yaws (dB, highest - lowest; the lowest view's yaw "
        "in brackets), trilinear / aniso / oiio / oiio16:\n\n| texture | theta | a | trilinear | "
        "aniso | oiio | oiio16 |\n|---|---|---|---|---|---|---|\n");
    for (const std::string& row : spread_rows) std::printf("%s\n", row.c_str());
  }
  return 0;
}

}  // namespace

std::vector<BenchCommand> FilterCommands() {
  return {{"filter", "grazing-plane filter benchmark: PSNR and ns/sample per mode", RunFilter}};
}

}  // namespace aperture::bench
