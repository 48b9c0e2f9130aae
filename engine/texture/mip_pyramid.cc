#include "texture/mip_pyramid.h"

#include <algorithm>
#include <cmath>

namespace aperture {

const char* FilterModeName(FilterMode mode) {
  switch (mode) {
    case FilterMode::kNearest:
      return "nearest";
    case FilterMode::kBilinear:
      return "bilinear";
    case FilterMode::kTrilinear:
      return "trilinear";
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
  const double x = u * img.width() - 0.5, y = v * img.height() - 0.5;
  const double fx0 = std::floor(x), fy0 = std::floor(y);
  const float fx = static_cast<float>(x - fx0), fy = static_cast<float>(y - fy0);
  const int x0 = static_cast<int>(fx0), y0 = static_cast<int>(fy0);
  const Rgba& a = Texel(l, x0, y0);
  const Rgba& b = Texel(l, x0 + 1, y0);
  const Rgba& c = Texel(l, x0, y0 + 1);
  const Rgba& d = Texel(l, x0 + 1, y0 + 1);
  return (a * (1 - fx) + b * fx) * (1 - fy) + (c * (1 - fx) + d * fx) * fy;
}

Rgba MipPyramid::Trilinear(const TextureFootprint& f) const {
  const Image& base = levels_[0];
  const float w = static_cast<float>(base.width()), h = static_cast<float>(base.height());
  const float len_x = std::hypot(f.dudx * w, f.dvdx * h);
  const float len_y = std::hypot(f.dudy * w, f.dvdy * h);
  const float rho = std::max(len_x, len_y);
  const float lod = rho > 1.0f ? std::log2(rho) : 0.0f;
  const int top = levels() - 1;
  if (lod >= static_cast<float>(top)) return Bilinear(top, f.u, f.v);
  const int l0 = static_cast<int>(lod);
  const float t = lod - static_cast<float>(l0);
  if (t == 0.0f) return Bilinear(l0, f.u, f.v);
  return Bilinear(l0, f.u, f.v) * (1 - t) + Bilinear(l0 + 1, f.u, f.v) * t;
}

}  // namespace aperture
