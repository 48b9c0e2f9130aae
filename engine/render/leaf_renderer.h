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
  LeafRenderer(const FrameGeometry& geometry, const PolygonShader& shader, AntiAliasing aa,
               Rgba sky)
      : geo_(geometry), shader_(shader), aa_(aa), shape_(ShapeOf(aa)), sky_(sky) {}

  // Not thread-safe (scratch buffers): one LeafRenderer per worker.
  void Render(const LeafWindow& leaf, Image& frame);

 private:
  void RenderMixed(const LeafWindow& leaf, Image& frame);

  const FrameGeometry& geo_;
  const PolygonShader& shader_;
  AntiAliasing aa_;
  AaFilterShape shape_;
  Rgba sky_;
  CellCoverage coverage_;
  std::vector<CellPiece> pieces_;
  std::vector<size_t> cell_begin_;
  struct Weighted {
    int polygon;
    double weight;
  };
  std::vector<Weighted> weights_;
};

}  // namespace aperture
