#include "render/leaf_renderer.h"

namespace aperture {

void LeafRenderer::Render(const LeafWindow& leaf, Image& image) {
  const PixelRect& r = leaf.rect;
  switch (leaf.kind) {
    case LeafWindow::Kind::kEmpty:
      for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x) Pixel(image, x, y) = sky_;
      return;
    case LeafWindow::Kind::kCovered:
      for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x)
          Pixel(image, x, y) = shader_.Shade(leaf.cover, x + 0.5, y + 0.5);
      return;
    case LeafWindow::Kind::kMixed:
      RenderMixed(leaf, image);
      return;
  }
}

void LeafRenderer::RenderMixed(const LeafWindow& leaf, Image& image) {
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
    }
  }
  cell_begin_.back() = pieces_.size();

  for (int py = 0; py < r.height(); ++py) {
    for (int px = 0; px < r.width(); ++px) {
      weights_.clear();
      for (int cy = 0; cy <= span; ++cy) {
        for (int cx = 0; cx <= span; ++cx) {
          const size_t cell = static_cast<size_t>(py + cy) * nx + (px + cx);
          for (size_t k = cell_begin_[cell]; k < cell_begin_[cell + 1]; ++k) {
            const double w = CellWeight(aa_, pieces_[k].moments, cx, cy);
            bool merged = false;
            for (Weighted& e : weights_)
              if (e.polygon == pieces_[k].polygon) e.weight += w, merged = true;
            if (!merged) weights_.push_back({pieces_[k].polygon, w});
          }
        }
      }
      const double x = r.x0 + px + 0.5, y = r.y0 + py + 0.5;
      float r_sum = 0, g_sum = 0, b_sum = 0;
      double total = 0;
      for (const Weighted& e : weights_) {
        const Rgba c = shader_.Shade(e.polygon, x, y);
        const float w = static_cast<float>(e.weight);
        r_sum += c.r * w, g_sum += c.g * w, b_sum += c.b * w;
        total += e.weight;
      }
      const float sky_w = static_cast<float>(std::max(0.0, 1.0 - total));
      Pixel(image, r.x0 + px, r.y0 + py) = {r_sum + sky_.r * sky_w, g_sum + sky_.g * sky_w,
                                            b_sum + sky_.b * sky_w, 1.0f};
    }
  }
}

}  // namespace aperture
