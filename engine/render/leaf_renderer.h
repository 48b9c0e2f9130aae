// Renders one Warnock leaf window into the frame.
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "base/image.h"
#include "raster/aa_filter.h"
#include "raster/cell_bins.h"
#include "raster/cell_coverage.h"
#include "raster/warnock.h"
#include "render/frame_memory.h"
#include "render/polygon_shader.h"
#include "render/visible_surfaces.h"

namespace aperture {

class LeafRenderer {
 public:
  // `image` holds the pixels of `region` of the frame (row 0 = the region's top row).
  // `stop` (may be empty) is asked after each row of a mixed leaf's cells and inside crowded
  // cells (CellCoverage::SetStop): a leaf of many busy cells stops within a row.
  // `sky` with alpha below 1 (a transparent sky): pixels get the alpha of what covers them.
  // `memory` (may be null): the frame's budget, which its buffers are held against after each
  // row of a leaf's cells and before a leaf's polygons are binned.
  LeafRenderer(const FrameGeometry& geometry, const PolygonShader& shader, AntiAliasing aa,
               Rgba sky, const PixelRect& region, std::function<bool()> stop = {},
               FrameMemory* memory = nullptr)
      : geo_(geometry),
        shader_(shader),
        aa_(aa),
        shape_(ShapeOf(aa)),
        sky_(sky),
        region_(region),
        memory_(memory) {
    coverage_.SetStop(stop);
    stop_ = std::move(stop);
  }

  // Not thread-safe (scratch buffers): one LeafRenderer per worker. False when the stop test
  // cut the leaf short, or its buffers would pass the frame's memory budget (its pixels are then
  // not to be used).
  bool Render(const LeafWindow& leaf, Image& image);
  // The bytes its buffers hold.
  size_t WorkingBytes() const;
  // Records the polygons visible in the wanted cells of the leaves it renders
  // (render/visible_surfaces.h) into `surfaces`; each cell is written by one leaf only.
  void RecordSurfaces(VisibleSurfaces* surfaces) {
    surfaces_ = surfaces;
    writer_.emplace(surfaces);
  }

 private:
  bool RenderMixed(const LeafWindow& leaf, Image& image);
  // The visible pieces of every cell of the leaf (pieces_, cell_begin_, reached_from_/to_), or
  // with `colour_sums` (a flat-coloured leaf under a box filter, its colours in flat_colours_)
  // only each cell's colour sum (cell_sums_). False when the stop test cut it short.
  bool ComputeCells(const PixelRect& r, std::span<const int> polygons, bool colour_sums);
  // Appends pixel (px, py)'s entries (one per polygon its aperture's cells hold) to entries_.
  void GatherPixel(int px, int py);
  // The pixel's value from its entries [first, last) with their colours: the weighted colours
  // (summed in float, in the entries' order), the sky in what they leave uncovered.
  template <typename ColourOf>
  Rgba PixelValue(size_t first, size_t last, ColourOf colour_of) const {
    float r_sum = 0, g_sum = 0, b_sum = 0;
    double total = 0;
    for (size_t e = first; e < last; ++e) {
      const Rgba c = colour_of(e);
      const float w = static_cast<float>(entries_[e].weight);
      r_sum += c.r * w, g_sum += c.g * w, b_sum += c.b * w;
      total += entries_[e].weight;
    }
    const float sky_w = static_cast<float>(std::max(0.0, 1.0 - total));
    return {r_sum + sky_.r * sky_w, g_sum + sky_.g * sky_w, b_sum + sky_.b * sky_w,
            PixelAlpha(total, sky_w)};
  }
  // A flat-coloured leaf under a box filter, from its cells' colour sums.
  void RenderFlatBox(const PixelRect& r, Image& image);
  struct CellSum {
    double r, g, b, area;  // a cell's pieces' colours by area, and their area
  };
  // The colours by area of pieces_[first, end).
  CellSum ColourSum(size_t first) const;
  void PrefetchPixels(const PixelRect& r, Image& image) const;
  // The pixels [from, to) of the leaf's row py whose cells hold any piece (the rest are sky, most
  // of a sparse frame's mixed leaves, and skip the entries), from reached_from_/reached_to_.
  std::pair<int, int> ReachedPixels(int py, int span, int width) const;
  // Shades every entry's point into colours_, each polygon's points in one batch (the texture
  // filters sample batches faster).
  void ShadeEntries(const PixelRect& r);
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
  FrameMemory* memory_;
  VisibleSurfaces* surfaces_ = nullptr;
  std::optional<VisibleSurfaces::Writer> writer_;
  // Whether this leaf writes absolute cell (kx, ky) of surfaces_: the cells of its own pixels, and
  // those past the region's last pixel for the leaves along its right and bottom edges.
  bool OwnsCell(const PixelRect& r, int kx, int ky) const {
    return (kx < r.x1 || r.x1 == region_.x1) && (ky < r.y1 || r.y1 == region_.y1);
  }
  // surfaces_'s record for cell (kx, ky): the polygons of pieces_[first, end).
  void RecordCellSurfaces(int kx, int ky, size_t first);
  // surfaces_'s records for the cells of `r` that one polygon (`cover` >= 0), the sky (-1) or an
  // unrecorded mix (-2) fills.
  void RecordWindowSurfaces(const PixelRect& r, int cover);
  size_t held_ = 0;  // what memory_ counts of this renderer's buffers
  // Holds the buffers against the frame's budget: false once it is passed.
  bool HoldMemory() { return memory_ == nullptr || memory_->Hold(held_, WorkingBytes()); }
  CellBins bins_;  // the leaf's polygons by cell
  std::vector<CellPiece> pieces_;
  int nx_ = 0;                       // cells per row of the leaf being rendered
  std::vector<double> nearest_;      // per polygon of the frame: its largest 1/depth (set per leaf)
  std::vector<int64_t> draw_order_;  // per polygon of the frame: its DrawOrder (set per leaf)
  struct DepthKey {
    uint64_t quantum;  // NearestQuantum of its nearest_
    int64_t order;     // its DrawOrder
    int polygon;
  };
  std::vector<DepthKey> keys_;  // the leaf's polygons, sorted nearest first
  std::vector<int> by_depth_;   // the leaf's polygons, nearest first, less hidden copies
  std::vector<std::pair<uint64_t, int>> copies_;  // (hash, polygon) of a run of equal quanta
  // by_depth_ from keys_, less the polygons that an identical one drawn over them hides.
  void SortedWithoutHiddenCopies();
  std::vector<size_t> cell_begin_;
  std::vector<int> reached_from_, reached_to_;  // per row of cells: its first, last + 1 with pieces
  // A polygon's weight in one pixel of the leaf, (px, py) from the leaf's top-left corner (the
  // renderer refuses frames over kMaxImageSide = 16384 a side): 16 bytes.
  struct Weighted {
    int polygon;
    uint16_t px, py;
    double weight;
  };
  static uint16_t Coordinate(int leaf_offset) { return static_cast<uint16_t>(leaf_offset); }
  absl::flat_hash_map<int, size_t> pixel_entry_;  // polygon -> its entry, in a crowded pixel
  std::vector<Weighted> entries_;                 // of every pixel of the leaf, row by row
  std::vector<size_t> pixel_begin_;  // pixel i's entries: [pixel_begin_[i], pixel_begin_[i + 1])
  std::vector<size_t> order_;        // entries by polygon
  std::vector<size_t> group_begin_;  // polygon group g of order_: [group_begin_[g], ...[g + 1])
  std::vector<int> slots_;           // each entry's group
  std::vector<int> slot_of_;         // per polygon of the frame: its group in this leaf, or -1
  std::vector<Vec2> points_;
  std::vector<Rgba> batch_, colours_;
  std::vector<Rgba> flat_colours_;              // a flat leaf's polygons' colours, by slot_of_
  std::vector<CellSum> cell_sums_, pair_sums_;  // RenderFlatBox's, per cell of the leaf
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
