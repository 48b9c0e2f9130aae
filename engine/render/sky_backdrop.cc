#include "render/sky_backdrop.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>

#include "scene/shading.h"

namespace aperture {
namespace {

// The world direction through frame point (x, y) (pixel corners at integers).
Vec3 ViewDirection(const FrustumTangents& frustum, const Mat3& orientation, int width, int height,
                   double x, double y) {
  return Normalize(orientation * CameraRay(frustum, width, height, x, y));
}

}  // namespace

SkyBackdrop::SkyBackdrop(const SkyDome& dome, const Camera& camera, int width, int height,
                         const PixelRect& region)
    : width_(width), height_(height) {
  const FrustumTangents frustum = ResolveFrustum(camera, width, height);
  const Mat3 orientation = camera.Orientation();
  // Nodes at the centres of frame pixels 0, step, 2 step, ... and the frame's last pixel, those
  // around the region: a frame rendered in regions has the same sky as the whole frame.
  i0_ = region.x0 / kSkyGridStep;
  j0_ = region.y0 / kSkyGridStep;
  columns_ = (region.x1 - 1) / kSkyGridStep + 2 - i0_;
  rows_ = (region.y1 - 1) / kSkyGridStep + 2 - j0_;
  nodes_.resize(static_cast<size_t>(columns_) * rows_);
  tbb::parallel_for(0, rows_, [&](int j) {
    const double y = std::min((j0_ + j) * kSkyGridStep, height - 1) + 0.5;
    for (int i = 0; i < columns_; ++i) {
      const double x = std::min((i0_ + i) * kSkyGridStep, width - 1) + 0.5;
      nodes_[static_cast<size_t>(j) * columns_ + i] =
          dome.Radiance(ViewDirection(frustum, orientation, width, height, x, y));
    }
  });
}

Rgba SkyBackdrop::At(int x, int y) const {
  Rgba c;
  Row(y, x, x + 1, &c);
  return c;
}

void SkyBackdrop::Row(int y, int x0, int x1, Rgba* out) const {
  // The row's sky at the nodes' columns (blended between the two rows of nodes around it), then
  // along the row between them.
  const int j = y / kSkyGridStep;
  const int span_y = std::min(kSkyGridStep, height_ - 1 - j * kSkyGridStep);
  const float fy = span_y > 0 ? static_cast<float>(y - j * kSkyGridStep) / span_y : 0.0f;
  const Rgba* top = &nodes_[static_cast<size_t>(j - j0_) * columns_];
  const Rgba* bottom = top + columns_;
  const auto column = [&](int i) { return top[i - i0_] * (1 - fy) + bottom[i - i0_] * fy; };
  int i = x0 / kSkyGridStep;
  Rgba left = column(i), right = column(i + 1);
  for (int x = x0; x < x1; ++x) {
    if (x / kSkyGridStep != i) {
      i = x / kSkyGridStep;
      left = right;
      right = column(i + 1);
    }
    const int span_x = std::min(kSkyGridStep, width_ - 1 - i * kSkyGridStep);
    const float fx = span_x > 0 ? static_cast<float>(x - i * kSkyGridStep) / span_x : 0.0f;
    Rgba c = left * (1 - fx) + right * fx;
    c.a = 1;
    out[x - x0] = c;
  }
}

Rgba SkyBackdrop::Exact(const SkyDome& dome, const Camera& camera, int width, int height, int x,
                        int y) {
  return dome.Radiance(ViewDirection(ResolveFrustum(camera, width, height), camera.Orientation(),
                                     width, height, x + 0.5, y + 0.5));
}

void CompositeSky(const SkyDome& dome, const Camera& camera, int width, int height,
                  const PixelRect& region, Image& image) {
  const SkyBackdrop sky(dome, camera, width, height, region);
  tbb::parallel_for(tbb::blocked_range<int>(0, region.height(), 16),
                    [&](const tbb::blocked_range<int>& rows) {
                      std::vector<Rgba> row(static_cast<size_t>(region.width()));
                      for (int py = rows.begin(); py < rows.end(); ++py) {
                        Rgba* pixels = &image.at(0, py);
                        // Rows the scene covers whole (most of the ground) need no sky.
                        int first = 0;
                        while (first < region.width() && pixels[first].a >= 1) ++first;
                        if (first == region.width()) continue;
                        sky.Row(region.y0 + py, region.x0 + first, region.x1, row.data());
                        for (int px = first; px < region.width(); ++px) {
                          Rgba& p = pixels[px];
                          const float open = std::max(0.0f, 1.0f - p.a);
                          const Rgba& s = row[px - first];
                          p.r += s.r * open, p.g += s.g * open, p.b += s.b * open;
                          p.a = 1;
                        }
                      }
                    });
}

}  // namespace aperture
