// What the raster pass saw in the cells that light points reach, kept for their pass
// (render/light_pass.h): the polygons visible in each cell. A light is hidden only by polygons
// nearer than it, and those that reach its footprint are visible in some of its cells (or hidden
// there by others nearer still): so a light's possible occluders are read from its few cells
// rather than searched for among the polygons of the frame.
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <vector>

#include "base/pixel_rect.h"

namespace aperture {

struct CellSurfaces {
  static constexpr int kMax = 16;
  // How many polygons are visible in the cell (0: the sky), or -1: not known (more than kMax, or
  // transparent surfaces, whose cells are not recorded).
  int8_t count;
  int32_t polygons[kMax];  // indices into the frame's polygons
};

// The cells of a frame region's filter grid: cell k covers [k + offset, k + offset + 1] on each
// axis (raster/aa_filter.h), k from the region's first pixel to its last plus `span`. Only the
// cells marked wanted (by tiles of kTile cells) are recorded and read; the rest is never touched.
class VisibleSurfaces {
 public:
  static constexpr int kTile = 8;

  VisibleSurfaces(const PixelRect& region, int span)
      : x0_(region.x0),
        y0_(region.y0),
        nx_(region.width() + span),
        ny_(region.height() + span),
        tiles_x_((nx_ + kTile - 1) / kTile),
        wanted_(static_cast<size_t>(tiles_x_) * ((ny_ + kTile - 1) / kTile), 0),
        cells_(new CellSurfaces[static_cast<size_t>(nx_) * ny_]) {}

  bool Holds(int kx, int ky) const {
    return kx >= x0_ && ky >= y0_ && kx < x0_ + nx_ && ky < y0_ + ny_;
  }
  // Marks the cells [kx0, kx1] x [ky0, ky1] (clipped to the grid) wanted.
  void Want(int kx0, int ky0, int kx1, int ky1) {
    const int tx0 = std::max(kx0 - x0_, 0) / kTile, tx1 = std::min(kx1 - x0_, nx_ - 1) / kTile;
    const int ty0 = std::max(ky0 - y0_, 0) / kTile, ty1 = std::min(ky1 - y0_, ny_ - 1) / kTile;
    for (int ty = ty0; ty <= ty1; ++ty)
      for (int tx = tx0; tx <= tx1; ++tx) wanted_[static_cast<size_t>(ty) * tiles_x_ + tx] = 1;
  }
  // Calls visit(kx, ky) for each wanted cell of [kx0, kx1) x [ky0, ky1), tile by tile.
  template <class Visit>
  void ForWantedCells(int kx0, int ky0, int kx1, int ky1, Visit visit) const {
    const int ty0 = (ky0 - y0_) / kTile, ty1 = (ky1 - 1 - y0_) / kTile;
    const int tx0 = (kx0 - x0_) / kTile, tx1 = (kx1 - 1 - x0_) / kTile;
    for (int ty = ty0; ty <= ty1; ++ty)
      for (int tx = tx0; tx <= tx1; ++tx) {
        if (!wanted_[static_cast<size_t>(ty) * tiles_x_ + tx]) continue;
        const int cx0 = std::max(kx0, x0_ + tx * kTile);
        const int cx1 = std::min(kx1, x0_ + (tx + 1) * kTile);
        const int cy0 = std::max(ky0, y0_ + ty * kTile);
        const int cy1 = std::min(ky1, y0_ + (ty + 1) * kTile);
        for (int ky = cy0; ky < cy1; ++ky)
          for (int kx = cx0; kx < cx1; ++kx) visit(kx, ky);
      }
  }
  bool Wanted(int kx, int ky) const {
    return wanted_[static_cast<size_t>((ky - y0_) / kTile) * tiles_x_ + (kx - x0_) / kTile] != 0;
  }
  CellSurfaces& at(int kx, int ky) {
    return cells_[static_cast<size_t>(ky - y0_) * nx_ + (kx - x0_)];
  }
  const CellSurfaces& at(int kx, int ky) const {
    return cells_[static_cast<size_t>(ky - y0_) * nx_ + (kx - x0_)];
  }
  // What it may hold: its marks, and the cells wanted (the others are never written).
  size_t Bytes() const {
    size_t wanted = 0;
    for (uint8_t w : wanted_) wanted += w;
    return wanted_.size() + wanted * kTile * kTile * sizeof(CellSurfaces);
  }

 private:
  int x0_, y0_, nx_, ny_, tiles_x_;
  std::vector<uint8_t> wanted_;
  // Not initialized: only wanted cells are written, then read.
  std::unique_ptr<CellSurfaces[]> cells_;
};

}  // namespace aperture
