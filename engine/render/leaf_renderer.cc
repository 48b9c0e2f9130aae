#include "render/leaf_renderer.h"

#include <algorithm>

namespace aperture {

bool LeafRenderer::Render(const LeafWindow& leaf, Image& image) {
  const PixelRect& r = leaf.rect;
  switch (leaf.kind) {
    case LeafWindow::Kind::kEmpty:
      for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x) Pixel(image, x, y) = sky_;
      return true;
    case LeafWindow::Kind::kCovered:
      for (int y = r.y0; y < r.y1; ++y)
        shader_.ShadeRow(leaf.cover, r.x0 + 0.5, y + 0.5, r.width(), &Pixel(image, r.x0, y));
      return true;
    case LeafWindow::Kind::kMixed:
      return RenderMixed(leaf, image);
  }
  return true;
}

bool LeafRenderer::RenderMixed(const LeafWindow& leaf, Image& image) {
  const PixelRect& r = leaf.rect;
  const int span = shape_.cells_per_axis - 1;  // extra cells beyond the pixels
  const int nx = r.width() + span, ny = r.height() + span;
  pieces_.clear();
  cell_begin_.assign(static_cast<size_t>(nx) * ny + 1, 0);
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      cell_begin_[static_cast<size_t>(j) * nx + i] = pieces_.size();
      const double cx = r.x0 + i + shape_.cell_offset + 0.5;
      const double cy = r.y0 + j + shape_.cell_offset + 0.5;
      coverage_.Compute(geo_.polygons, leaf.polygons, cx, cy, shape_.needs_moments, pieces_);
      if (coverage_.Stopped()) return false;
    }
  }
  cell_begin_.back() = pieces_.size();

  // Each pixel's polygons and weights, in the order the colours are summed.
  entries_.clear();
  pixel_begin_.clear();
  for (int py = 0; py < r.height(); ++py) {
    for (int px = 0; px < r.width(); ++px) {
      pixel_begin_.push_back(entries_.size());
      const size_t first = entries_.size();
      // A pixel's pieces are few but for crowded cells (a whole scene in one pixel), whose
      // polygons are found through a map rather than by a scan of the pixel's entries.
      size_t pieces = 0;
      for (int cy = 0; cy <= span; ++cy) {
        const size_t row = static_cast<size_t>(py + cy) * nx + px;
        pieces += cell_begin_[row + span + 1] - cell_begin_[row];
      }
      const bool crowded = pieces > kCrowdedPixelPieces;
      if (crowded) pixel_entry_.clear();
      for (int cy = 0; cy <= span; ++cy) {
        for (int cx = 0; cx <= span; ++cx) {
          const size_t cell = static_cast<size_t>(py + cy) * nx + (px + cx);
          for (size_t k = cell_begin_[cell]; k < cell_begin_[cell + 1]; ++k) {
            const double w = CellWeight(aa_, pieces_[k].moments, cx, cy);
            const int polygon = pieces_[k].polygon;
            size_t e = first;
            if (crowded) {
              e = pixel_entry_.try_emplace(polygon, entries_.size()).first->second;
            } else {
              while (e < entries_.size() && entries_[e].polygon != polygon) ++e;
            }
            if (e < entries_.size())
              entries_[e].weight += w;
            else
              entries_.push_back({polygon, w, {r.x0 + px + 0.5, r.y0 + py + 0.5}});
          }
        }
      }
    }
  }
  pixel_begin_.push_back(entries_.size());

  // Shade every polygon's points in one batch (the texture filters sample batches faster).
  order_.resize(entries_.size());
  for (size_t i = 0; i < order_.size(); ++i) order_[i] = i;
  std::stable_sort(order_.begin(), order_.end(),
                   [&](size_t a, size_t b) { return entries_[a].polygon < entries_[b].polygon; });
  colours_.resize(entries_.size());
  for (size_t begin = 0; begin < order_.size();) {
    const int polygon = entries_[order_[begin]].polygon;
    size_t end = begin;
    points_.clear();
    for (; end < order_.size() && entries_[order_[end]].polygon == polygon; ++end)
      points_.push_back(entries_[order_[end]].point);
    batch_.resize(points_.size());
    shader_.ShadeMany(polygon, points_.data(), static_cast<int>(points_.size()), batch_.data());
    for (size_t i = begin; i < end; ++i) colours_[order_[i]] = batch_[i - begin];
    begin = end;
  }

  for (int py = 0; py < r.height(); ++py) {
    for (int px = 0; px < r.width(); ++px) {
      const size_t pixel = static_cast<size_t>(py) * r.width() + px;
      float r_sum = 0, g_sum = 0, b_sum = 0;
      double total = 0;
      for (size_t e = pixel_begin_[pixel]; e < pixel_begin_[pixel + 1]; ++e) {
        const Rgba& c = colours_[e];
        const float w = static_cast<float>(entries_[e].weight);
        r_sum += c.r * w, g_sum += c.g * w, b_sum += c.b * w;
        total += entries_[e].weight;
      }
      const float sky_w = static_cast<float>(std::max(0.0, 1.0 - total));
      Pixel(image, r.x0 + px, r.y0 + py) = {r_sum + sky_.r * sky_w, g_sum + sky_.g * sky_w,
                                            b_sum + sky_.b * sky_w, 1.0f};
    }
  }
  return true;
}

}  // namespace aperture
