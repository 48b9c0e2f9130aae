#include "texture/mip_pyramid.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include "texture/trilinear_kernels.h"

namespace aperture {
namespace {

// log2 to within 0.005 (exponent plus a quadratic in the mantissa): a level-of-detail blend
// weight needs no more, and std::log2 was a tenth of the sampling time.
float FastLog2(float x) {
  const uint32_t bits = std::bit_cast<uint32_t>(x);
  const float exponent = static_cast<float>(static_cast<int>((bits >> 23) & 255) - 127);
  const float m = std::bit_cast<float>((bits & 0x7fffffu) | 0x3f800000u);  // in [1, 2)
  return exponent + (-0.34484843f * m + 2.02466578f) * m - 0.67487759f;
}

}  // namespace

const char* FilterModeName(FilterMode mode) {
  switch (mode) {
    case FilterMode::kNearest:
      return "nearest";
    case FilterMode::kBilinear:
      return "bilinear";
    case FilterMode::kTrilinear:
      return "trilinear";
    case FilterMode::kAniso:
      return "aniso";
    case FilterMode::kOiio:
      return "oiio";
    case FilterMode::kReference:
      return "reference";
  }
  return "?";
}

MipPyramid::MipPyramid(Image base) {
  levels_.push_back(std::move(base));
  while (levels_.back().width() > 1 || levels_.back().height() > 1) {
    const Image& src = levels_.back();
    const int w = std::max(1, src.width() / 2), h = std::max(1, src.height() / 2);
    const int sx = src.width() / w, sy = src.height() / h;  // 2, or 1 on a collapsed axis
    const float scale = 1.0f / static_cast<float>(sx * sy);
    Image dst(w, h);
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        Rgba sum;
        for (int j = 0; j < sy; ++j)
          for (int i = 0; i < sx; ++i) sum = sum + src.at(x * sx + i, y * sy + j);
        dst.at(x, y) = sum * scale;
      }
    }
    levels_.push_back(std::move(dst));
  }
}

Rgba MipPyramid::Nearest(double u, double v) const {
  const Image& img = levels_[0];
  const int x = static_cast<int>(std::floor(u * img.width()));
  const int y = static_cast<int>(std::floor(v * img.height()));
  return Texel(0, x, y);
}

Rgba MipPyramid::Bilinear(int l, double u, double v) const {
  const Image& img = levels_[l];
  const int w = img.width(), h = img.height();
  const float x = static_cast<float>(u * w) - 0.5f, y = static_cast<float>(v * h) - 0.5f;
  const float fx0 = std::floor(x), fy0 = std::floor(y);
  const float fx = x - fx0, fy = y - fy0;
  const int x0 = static_cast<int>(fx0) & (w - 1), x1 = (x0 + 1) & (w - 1);
  const int y0 = static_cast<int>(fy0) & (h - 1), y1 = (y0 + 1) & (h - 1);
  const Rgba* row0 = &img.at(0, y0);
  const Rgba* row1 = &img.at(0, y1);
  return (row0[x0] * (1 - fx) + row0[x1] * fx) * (1 - fy) +
         (row1[x0] * (1 - fx) + row1[x1] * fx) * fy;
}

Rgba MipPyramid::Trilinear(const TextureFootprint& f) const {
  const Image& base = levels_[0];
  const float w = static_cast<float>(base.width()), h = static_cast<float>(base.height());
  const float ux = f.dudx * w, vx = f.dvdx * h, uy = f.dudy * w, vy = f.dvdy * h;
  const float rho2 = std::max(ux * ux + vx * vx, uy * uy + vy * vy);  // longer axis, squared
  const float lod = rho2 > 1.0f ? 0.5f * FastLog2(rho2) : 0.0f;
  const int top = levels() - 1;
  if (lod >= static_cast<float>(top)) return Bilinear(top, f.u, f.v);
  const int l0 = static_cast<int>(lod);
  const float t = lod - static_cast<float>(l0);
  if (t == 0.0f) return Bilinear(l0, f.u, f.v);
  return Bilinear(l0, f.u, f.v) * (1 - t) + Bilinear(l0 + 1, f.u, f.v) * t;
}

void NearestSampler::SampleMany(const TextureFootprint* in, Rgba* out, int count) const {
  for (int i = 0; i < count; ++i) out[i] = pyramid_.Nearest(in[i].u, in[i].v);
}

void BilinearSampler::SampleMany(const TextureFootprint* in, Rgba* out, int count) const {
  for (int i = 0; i < count; ++i) out[i] = pyramid_.Bilinear(0, in[i].u, in[i].v);
}

void TrilinearSampler::SampleMany(const TextureFootprint* in, Rgba* out, int count) const {
  for (int i = 0; i < count; ++i) out[i] = pyramid_.Trilinear(in[i]);
}

void TrilinearSampler::SampleBatch(const FootprintBatch& in, Rgba* out) const {
  static const TrilinearBatchFn kernel = BestTrilinearBatch();
  kernel(pyramid_, in, out);
}

}  // namespace aperture
