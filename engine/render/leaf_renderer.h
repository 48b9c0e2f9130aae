// Renders one Warnock leaf window into the frame.
#pragma once

#include <functional>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "base/image.h"
#include "raster/aa_filter.h"
#include "raster/cell_bins.h"
#include "raster/cell_coverage.h"
#include "raster/warnock.h"
#include "render/polygon_shader.h"

namespace aperture {

class LeafRenderer {
 public:
  // `image` holds the pixels of `region` of the frame (row 0 = the region's top row).
  // `stop` (may be empty) is asked after each row of a mixed leaf's cells and inside crowded
  // cells (CellCoverage::SetStop): a leaf of many busy cells stops within a row.
  // `sky` with alpha below 1 (a transparent sky): pixels get the alpha of what covers them.
  LeafRenderer(const FrameGeometry& geometry, const PolygonShader& shader, AntiAliasing aa,
               Rgba sky, const PixelRect& region, std::function<bool()> stop = {})
      : geo_(geometry), shader_(shader), aa_(aa), shape_(ShapeOf(aa)), sky_(sky), region_(region) {
    coverage_.SetStop(stop);
    stop_ = std::move(stop);
  }

  // Not thread-safe (scratch buffers): one LeafRenderer per worker. False when the stop test
  // cut the leaf short (its pixels are then not to be used).
  bool Render(const LeafWindow& leaf, Image& image);

 private:
  bool RenderMixed(const LeafWindow& leaf, Image& image);
  // Shades every entry's point into colours_, each polygon's points in one batch (the texture
  // filters sample batches faster).
  void ShadeEntries();
  // A mixed leaf with MASK or BLEND polygons (ScreenPolygon::transparent), composited exactly.
  bool RenderMixedTransparent(const LeafWindow& leaf, Image& image);
  // The transparent polygons of `leaf` that reach the cell centred at (cx, cy), nearest at its
  // centre first, at most kMaxLayers of them, into layers_.
  void TransparentLayers(const LeafWindow& leaf, double cx, double cy);
  // The alpha of the pixel's finished value: 1 over an opaque sky, else what covers it.
  float PixelAlpha(double covered, float sky_weight) const {
    return sky_.a == 1.0f ? 1.0f : static_cast<float>(std::min(1.0, covered)) + sky_.a * sky_weight;
  }
  // Transparent polygons per cell that are composited exactly: each subset of them is a
  // visibility pass of its own (2^kMaxLayers at most). Any further ones (rare: more than four
  // semi-transparent surfaces in one cell) are drawn as if opaque.
  static constexpr size_t kMaxLayers = 4;
  // More pieces than this in a pixel's cells: its polygons are merged through a map.
  static constexpr size_t kCrowdedPixelPieces = 32;
  Rgba& Pixel(Image& image, int x, int y) const { return image.at(x - region_.x0, y - region_.y0); }

  const FrameGeometry& geo_;
  const PolygonShader& shader_;
  AntiAliasing aa_;
  AaFilterShape shape_;
  Rgba sky_;
  PixelRect region_;
  CellCoverage coverage_;
  std::function<bool()> stop_;
  CellBins bins_;  // the leaf's polygons by cell
  std::vector<CellPiece> pieces_;
  std::vector<size_t> cell_begin_;
  struct Weighted {
    int polygon;
    double weight;
    Vec2 point;  // the pixel centre
  };
  absl::flat_hash_map<int, size_t> pixel_entry_;  // polygon -> its entry, in a crowded pixel
  std::vector<Weighted> entries_;                 // of every pixel of the leaf, row by row
  std::vector<size_t> pixel_begin_;  // pixel i's entries: [pixel_begin_[i], pixel_begin_[i + 1])
  std::vector<size_t> order_;        // entries by polygon
  std::vector<size_t> group_begin_;  // polygon group g of order_: [group_begin_[g], ...[g + 1])
  std::vector<int> slots_;           // each entry's group
  std::vector<int> slot_of_;         // per polygon of the frame: its group in this leaf, or -1
  std::vector<Vec2> points_;
  std::vector<Rgba> batch_, colours_;
  // The transparent path's passes: a cell's passes are passes_[cell_begin_[c], cell_begin_[c + 1])
  // (its pieces each pass's [begin, end) of pieces_); bit j of `included` says whether the cell's
  // layer j took part. Its layers are cell_layers_[layer_begin_[c], layer_begin_[c + 1]).
  struct Pass {
    unsigned included;
    size_t begin, end;
  };
  std::vector<Pass> passes_;
  std::vector<int> layers_, cell_layers_, candidates_;
  std::vector<uint32_t> needed_;  // per cell, bit s: layer subset s carries weight at some pixel
  std::vector<size_t> layer_begin_;
};

}  // namespace aperture
