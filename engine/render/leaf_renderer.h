// Renders one Warnock leaf window into the frame.
#pragma once

#include <vector>

#include "raster/aa_filter.h"
#include "raster/cell_coverage.h"
#include "raster/warnock.h"
#include "render/polygon_shader.h"
#include "texture/image.h"

namespace aperture {

class LeafRenderer {
 public:
  // `image` holds the pixels of `region` of the frame (row 0 = the region's top row).
  LeafRenderer(const FrameGeometry& geometry, const PolygonShader& shader, AntiAliasing aa,
               Rgba sky, const PixelRect& region)
      : geo_(geometry), shader_(shader), aa_(aa), shape_(ShapeOf(aa)), sky_(sky), region_(region) {}

  // Not thread-safe (scratch buffers): one LeafRenderer per worker.
  void Render(const LeafWindow& leaf, Image& image);

 private:
  void RenderMixed(const LeafWindow& leaf, Image& image);
  Rgba& Pixel(Image& image, int x, int y) const { return image.at(x - region_.x0, y - region_.y0); }

  const FrameGeometry& geo_;
  const PolygonShader& shader_;
  AntiAliasing aa_;
  AaFilterShape shape_;
  Rgba sky_;
  PixelRect region_;
  CellCoverage coverage_;
  std::vector<CellPiece> pieces_;
  std::vector<size_t> cell_begin_;
  struct Weighted {
    int polygon;
    double weight;
    Vec2 point;  // the pixel centre
  };
  std::vector<Weighted> entries_;    // of every pixel of the leaf, row by row
  std::vector<size_t> pixel_begin_;  // pixel i's entries: [pixel_begin_[i], pixel_begin_[i + 1])
  std::vector<size_t> order_;        // entries by polygon
  std::vector<Vec2> points_;
  std::vector<Rgba> batch_, colours_;
};

}  // namespace aperture
