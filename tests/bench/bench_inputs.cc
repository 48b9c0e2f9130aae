#include "bench/bench_inputs.h"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_split.h"
#include "io/exr_writer.h"
#include "texture/image_file.h"

namespace aperture {

int bench::Fail(const char* command, const std::string& message) {
  std::fprintf(stderr, "aperture-bench %s: %s\n", command, message.c_str());
  return 2;
}

absl::StatusOr<std::vector<double>> ParseNumbers(const std::string& text, const char* what) {
  std::vector<double> out;
  for (absl::string_view part : absl::StrSplit(text, ',')) {
    double value = 0;
    if (!absl::SimpleAtod(part, &value) || !std::isfinite(value))
      return absl::InvalidArgumentError(absl::StrCat(what, ": '", part, "' is not a number"));
    out.push_back(value);
  }
  return out;
}

absl::StatusOr<std::vector<BenchTexture>> LoadBenchTextures(const std::string& list,
                                                            const std::string& data_dir) {
  std::vector<BenchTexture> out;
  for (absl::string_view part : absl::StrSplit(list, ',')) {
    const std::string name(part);
    if (name == "checker") {
      out.push_back({"checker", MakeCheckerboard(1024, 8, {1, 1, 1, 1}, {0, 0, 0, 1})});
      continue;
    }
    std::string path = name;
    if (!std::filesystem::exists(path)) path = (std::filesystem::path(data_dir) / name).string();
    if (!std::filesystem::exists(path)) path += ".png";
    auto image = LoadImageFile(path);
    if (!image.ok()) return image.status();
    out.push_back({std::filesystem::path(path).stem().string(), ResizeToPowerOfTwo(*image)});
  }
  return out;
}

absl::StatusOr<Image> CachedReference(const GrazingPlaneView& view, const BenchTexture& texture,
                                      double density, int max_per_side, int min_per_side,
                                      const std::string& cache_dir, bool* cached) {
  const std::string path =
      (std::filesystem::path(cache_dir) /
       absl::StrCat("ref_", texture.name, "_", texture.image.width(), "_p", view.pitch_deg, "_y",
                    view.yaw_deg, "_a", view.aperture, "_d", density, "_m", max_per_side, "_n",
                    min_per_side, "_", view.width, "x", view.height,
                    view.origin_u == 0 && view.origin_v == 0
                        ? ""
                        : absl::StrFormat("_o%.6f_%.6f", view.origin_u, view.origin_v),
                    ".exr"))
          .string();
  *cached = std::filesystem::exists(path);
  if (*cached) return LoadImageFile(path);
  Image ref = RenderGroundReference(view, texture.image, density, max_per_side, min_per_side);
  ExrOptions exr;
  exr.pixel_type = ExrPixelType::kFloat;
  if (auto s = WriteExrFile(ref, exr, path); !s.ok()) return s;
  return ref;
}

}  // namespace aperture
