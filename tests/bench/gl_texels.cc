#include "gl_texels.h"

#include <algorithm>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "texture/packed/packed_sampler.h"
#include "texture/packed/rgba8_image.h"

namespace aperture {
namespace {

uint8_t ToByte(float v) {
  return static_cast<uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
}

// The largest level of the pyramid within `max_side`, its colours no longer premultiplied.
GlTexels FromPyramid(const SceneTexture& texture, int max_side) {
  const MipPyramid& pyramid = *texture.pyramid;
  int level = 0;
  while (level + 1 < pyramid.levels() &&
         std::max(pyramid.level(level).width(), pyramid.level(level).height()) > max_side)
    ++level;
  const Image& image = pyramid.level(level);
  GlTexels out;
  out.width = image.width();
  out.height = image.height();
  out.rgba.resize(static_cast<size_t>(out.width) * out.height * 4);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      Rgba c = image.at(x, y);
      if (texture.has_alpha && c.a > 0) c = {c.r / c.a, c.g / c.a, c.b / c.a, c.a};
      uint8_t* t = &out.rgba[(static_cast<size_t>(y) * out.width + x) * 4];
      t[0] = ToByte(c.r), t[1] = ToByte(c.g), t[2] = ToByte(c.b), t[3] = ToByte(c.a);
    }
  out.source = absl::StrCat("raster ", pyramid.level(0).width(), "x", pyramid.level(0).height(),
                            level > 0 ? absl::StrCat(", its mip level ", level) : "");
  return out;
}

// Every texel of the packed texture, averaged over blocks of `factor` x `factor` (a power of two)
// until the sides are within `max_side`.
GlTexels FromPacked(const packed::PackedTextureView& view, int max_side) {
  const packed::IndexedImage indexed = packed::UnpackTexture(view);
  int factor = 1;
  while (static_cast<int>(std::max(indexed.width, indexed.height)) / factor > max_side) factor *= 2;
  GlTexels out;
  out.width = std::max(1, static_cast<int>(indexed.width) / factor);
  out.height = std::max(1, static_cast<int>(indexed.height) / factor);
  out.rgba.resize(static_cast<size_t>(out.width) * out.height * 4);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      uint32_t sum[4] = {0, 0, 0, 0};
      for (int j = 0; j < factor; ++j)
        for (int i = 0; i < factor; ++i) {
          const uint32_t c = indexed.palette[indexed.at(static_cast<uint32_t>(x * factor + i),
                                                        static_cast<uint32_t>(y * factor + j))];
          for (int k = 0; k < 4; ++k) sum[k] += packed::Channel(c, k);
        }
      uint8_t* t = &out.rgba[(static_cast<size_t>(y) * out.width + x) * 4];
      const uint32_t n = static_cast<uint32_t>(factor * factor);
      for (int k = 0; k < 4; ++k) t[k] = static_cast<uint8_t>((sum[k] + n / 2) / n);
    }
  out.source = absl::StrCat(
      "packed vector ", indexed.width, "x", indexed.height, ", ", view.run_count(),
      " runs, decoded",
      factor > 1 ? absl::StrCat(" and box-averaged to ", out.width, "x", out.height) : "");
  return out;
}

}  // namespace

absl::StatusOr<GlTexels> GlTexelsOf(const SceneTexture& texture, int max_side) {
  if (texture.pyramid) return FromPyramid(texture, max_side);
  if (texture.packed && texture.packed_area) {
    const auto* sampler =
        dynamic_cast<const packed::PackedTextureSampler*>(texture.packed_area.get());
    if (sampler != nullptr) return FromPacked(sampler->texture(), max_side);
  }
  return absl::UnimplementedError(
      absl::StrCat("texture ", texture.id, ": neither a raster pyramid nor a packed texture"));
}

Rgba MeanColour(const SceneTexture& texture) {
  const TextureSampler& sampler = **texture.Sampler(FilterMode::kNearest);  // never fails
  constexpr int kGrid = 64;
  Rgba sum;
  for (int j = 0; j < kGrid; ++j)
    for (int i = 0; i < kGrid; ++i) {
      TextureFootprint f;
      f.u = (i + 0.5) / kGrid;
      f.v = (j + 0.5) / kGrid;
      sum = sum + sampler.Sample(f);
    }
  return sum * (1.0f / (kGrid * kGrid));
}

}  // namespace aperture
