// What the raster pass saw in the cells that light points reach, kept for their pass
// (render/light_pass.h): the polygons visible in each cell. A light is hidden only by polygons
// nearer than it, and those that reach its footprint are visible in some of its cells (or hidden
// there by others nearer still): so a light's possible occluders are read from its few cells
// rather than searched for among the polygons of the frame.
#pragma once

#include <algorithm>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <vector>

#include "base/pixel_rect.h"

namespace aperture {

// How many polygons are visible in a cell: 0 the sky, kUnknown more than kMaxPolygons, or
// transparent surfaces (whose cells are not recorded).
inline constexpr int8_t kUnknownSurfaces = -1;

// The cells of a frame region's filter grid: cell k covers [k + offset, k + offset + 1] on each
// axis (raster/aa_filter.h), k from the region's first pixel to its last plus `span`. Only the
// cells marked wanted are recorded and read; the rest is never touched. The marks are kept by
// cell and by tile of kTile x kTile cells, so that a window far from any light is passed over a
// tile at a time.
class VisibleSurfaces {
 public:
  static constexpr int kTile = 8;
  // The most polygons a cell keeps.
  static constexpr int kMaxPolygons = 16;

  VisibleSurfaces(const PixelRect& region, int span)
      : x0_(region.x0),
        y0_(region.y0),
        nx_(region.width() + span),
        ny_(region.height() + span),
        tiles_x_((nx_ + kTile - 1) / kTile),
        wanted_(static_cast<size_t>(tiles_x_) * ((ny_ + kTile - 1) / kTile), 0),
        cell_wanted_(static_cast<size_t>(nx_) * ny_, 0),
        counts_(new int8_t[static_cast<size_t>(nx_) * ny_]),
        first_(new int32_t[static_cast<size_t>(nx_) * ny_]),
        more_(new More[static_cast<size_t>(nx_) * ny_]) {}

  bool Holds(int kx, int ky) const {
    return kx >= x0_ && ky >= y0_ && kx < x0_ + nx_ && ky < y0_ + ny_;
  }
  // Marks the cells [kx0, kx1] x [ky0, ky1] (clipped to the grid) wanted.
  void Want(int kx0, int ky0, int kx1, int ky1) {
    const int tx0 = std::max(kx0 - x0_, 0) / kTile, tx1 = std::min(kx1 - x0_, nx_ - 1) / kTile;
    const int ty0 = std::max(ky0 - y0_, 0) / kTile, ty1 = std::min(ky1 - y0_, ny_ - 1) / kTile;
    for (int ty = ty0; ty <= ty1; ++ty)
      for (int tx = tx0; tx <= tx1; ++tx) wanted_[static_cast<size_t>(ty) * tiles_x_ + tx] = 1;
    for (int ky = std::max(ky0, y0_); ky <= std::min(ky1, y0_ + ny_ - 1); ++ky)
      for (int kx = std::max(kx0, x0_); kx <= std::min(kx1, x0_ + nx_ - 1); ++kx) {
        uint8_t& w = cell_wanted_[Index(kx, ky)];
        wanted_cells_ += w == 0;
        w = 1;
      }
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
          for (int kx = cx0; kx < cx1; ++kx)
            if (cell_wanted_[Index(kx, ky)]) visit(kx, ky);
      }
  }
  bool Wanted(int kx, int ky) const { return cell_wanted_[Index(kx, ky)] != 0; }
  // The number of polygons visible in cell (kx, ky), or kUnknownSurfaces.
  int count(int kx, int ky) const { return counts_[Index(kx, ky)]; }

  // Where one worker of the raster pass appends the lists of its cells past their first polygon
  // (each worker its own, so that they record at once without locks).
  class Writer {
   public:
    explicit Writer(VisibleSurfaces* surfaces) : surfaces_(surfaces) {
      const std::lock_guard<std::mutex> lock(surfaces->writers_mutex_);
      id_ = static_cast<uint16_t>(surfaces->lists_.size());
      list_ = &surfaces->lists_.emplace_back();
    }
    // Records that `count` polygons are visible in cell (kx, ky), polygon(k) the k-th (an index
    // into the frame's polygons); more than kMaxPolygons are recorded as unknown.
    template <class Polygon>
    void Record(int kx, int ky, size_t count, Polygon polygon) {
      VisibleSurfaces& s = *surfaces_;
      const size_t i = s.Index(kx, ky);
      if (count > kMaxPolygons) {
        s.counts_[i] = kUnknownSurfaces;
        return;
      }
      s.counts_[i] = static_cast<int8_t>(count);
      if (count == 0) return;
      s.first_[i] = polygon(0);
      if (count == 1) return;
      s.more_[i] = {id_, static_cast<uint32_t>(list_->size())};
      for (size_t k = 1; k < count; ++k) list_->push_back(polygon(k));
    }
    void RecordUnknown(int kx, int ky) {
      surfaces_->counts_[surfaces_->Index(kx, ky)] = kUnknownSurfaces;
    }

   private:
    VisibleSurfaces* surfaces_;
    uint16_t id_;
    std::vector<int32_t>* list_;
  };

  // Calls visit(index) for each polygon recorded visible in cell (kx, ky).
  template <class Visit>
  void ForPolygons(int kx, int ky, Visit visit) const {
    const size_t i = Index(kx, ky);
    const int count = counts_[i];
    if (count <= 0) return;
    visit(first_[i]);
    if (count == 1) return;
    const int32_t* more = lists_[more_[i].list].data() + more_[i].at;
    for (int k = 1; k < count; ++k) visit(more[k - 1]);
  }
  // What it may hold: its marks, and the cells wanted (the others are never written) with
  // kMaxPolygons each at most.
  size_t Bytes() const {
    return wanted_.size() + cell_wanted_.size() +
           wanted_cells_ * (sizeof(int8_t) + sizeof(int32_t) + sizeof(More) +
                            (kMaxPolygons - 1) * sizeof(int32_t));
  }

 private:
  // Where a cell's list goes on past its first polygon: lists_[list], from `at`.
  struct More {
    uint16_t list;
    uint32_t at;
  };
  size_t Index(int kx, int ky) const { return static_cast<size_t>(ky - y0_) * nx_ + (kx - x0_); }

  int x0_, y0_, nx_, ny_, tiles_x_;
  std::vector<uint8_t> wanted_, cell_wanted_;
  size_t wanted_cells_ = 0;
  // Not initialized: only wanted cells are written, then read. Dense, one entry per cell: a light
  // reads the cells of its footprint, most of which see one polygon, and neighbouring cells share
  // cache lines.
  std::unique_ptr<int8_t[]> counts_;
  std::unique_ptr<int32_t[]> first_;
  std::unique_ptr<More[]> more_;
  // The writers' lists (a deque: a writer's list stays where it is while others are added).
  std::deque<std::vector<int32_t>> lists_;
  std::mutex writers_mutex_;
};

}  // namespace aperture
