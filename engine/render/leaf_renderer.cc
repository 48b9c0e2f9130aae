#include "render/leaf_renderer.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "base/held_bytes.h"
#include "raster/depth_order.h"
#include "raster/identical_polygons.h"

namespace aperture {

bool LeafRenderer::Render(const LeafWindow& leaf, Image& image) {
  const PixelRect& r = leaf.rect;
  switch (leaf.kind) {
    case LeafWindow::Kind::kEmpty:
      for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x) Pixel(image, x, y) = sky_;
      if (surfaces_ != nullptr) RecordWindowSurfaces(r, -1);
      return true;
    case LeafWindow::Kind::kCovered:
      for (int y = r.y0; y < r.y1; ++y)
        shader_.ShadeRow(leaf.cover, r.x0 + 0.5, y + 0.5, r.width(), &Pixel(image, r.x0, y));
      if (surfaces_ != nullptr) RecordWindowSurfaces(r, leaf.cover);
      return true;
    case LeafWindow::Kind::kMixed:
      return RenderMixed(leaf, image);
  }
  return true;
}

void LeafRenderer::RecordWindowSurfaces(const PixelRect& r, int cover) {
  // The window's own cells (those past the region's last pixel for its right and bottom edges),
  // a wanted tile at a time: most of a frame is far from any light.
  const int span = shape_.cells_per_axis - 1;
  const int kx1 = r.x1 == region_.x1 ? r.x1 + span : r.x1;
  const int ky1 = r.y1 == region_.y1 ? r.y1 + span : r.y1;
  surfaces_->ForWantedCells(r.x0, r.y0, kx1, ky1, [&](int kx, int ky) {
    if (cover < -1)
      writer_->RecordUnknown(kx, ky);
    else
      writer_->Record(kx, ky, cover == -1 ? 0 : 1, [&](size_t) { return cover; });
  });
}

void LeafRenderer::RecordCellSurfaces(int kx, int ky, size_t first) {
  writer_->Record(kx, ky, pieces_.size() - first,
                  [&](size_t k) { return pieces_[first + k].polygon; });
}

void LeafRenderer::ShadeEntries(const PixelRect& r) {
  // The entries grouped by polygon (a counting sort, stable: each polygon's points keep their
  // order), the groups in the order their polygons first appear.
  if (slot_of_.size() < geo_.polygons.size()) slot_of_.assign(geo_.polygons.size(), -1);
  group_begin_.clear();
  slots_.resize(entries_.size());
  for (size_t e = 0; e < entries_.size(); ++e) {
    int& slot = slot_of_[entries_[e].polygon];
    if (slot < 0) {
      slot = static_cast<int>(group_begin_.size());
      group_begin_.push_back(0);
    }
    slots_[e] = slot;
    ++group_begin_[slot];
  }
  size_t sum = 0;
  for (size_t& g : group_begin_) sum += std::exchange(g, sum);
  group_begin_.push_back(sum);
  order_.resize(entries_.size());
  for (size_t e = 0; e < entries_.size(); ++e) order_[group_begin_[slots_[e]]++] = e;
  for (size_t g = group_begin_.size() - 1; g > 0; --g) group_begin_[g] = group_begin_[g - 1];
  group_begin_[0] = 0;

  colours_.resize(entries_.size());
  for (size_t g = 0; g + 1 < group_begin_.size(); ++g) {
    const size_t begin = group_begin_[g], end = group_begin_[g + 1];
    const int polygon = entries_[order_[begin]].polygon;
    slot_of_[polygon] = -1;  // ready for the next leaf
    points_.clear();
    for (size_t i = begin; i < end; ++i) {
      const Weighted& entry = entries_[order_[i]];
      points_.push_back({r.x0 + entry.px + 0.5, r.y0 + entry.py + 0.5});
    }
    batch_.resize(points_.size());
    shader_.ShadeMany(polygon, points_.data(), static_cast<int>(points_.size()), batch_.data());
    for (size_t i = begin; i < end; ++i) colours_[order_[i]] = batch_[i - begin];
  }
}

// The leaf's rows are short runs of a large frame, which the hardware prefetcher does not follow:
// written cold, each line of a mixed leaf's pixels stalls the final pass. Asked for here, they
// arrive while the leaf's cells are computed.
void LeafRenderer::PrefetchPixels(const PixelRect& r, Image& image) const {
  constexpr int kLine = 64;
  for (int y = r.y0; y < r.y1; ++y) {
    const char* first = reinterpret_cast<const char*>(&Pixel(image, r.x0, y));
    const char* last = reinterpret_cast<const char*>(&Pixel(image, r.x1 - 1, y));
    for (const char* p = first; p <= last; p += kLine) __builtin_prefetch(p, 1, 3);
    __builtin_prefetch(last, 1, 3);
  }
}

std::pair<int, int> LeafRenderer::ReachedPixels(int py, int span, int width) const {
  int from = width, to = 0;
  for (int cy = 0; cy <= span; ++cy) {
    if (reached_from_[py + cy] >= reached_to_[py + cy]) continue;
    from = std::min(from, std::max(0, reached_from_[py + cy] - span));
    to = std::max(to, std::min(width, reached_to_[py + cy]));
  }
  return from < to ? std::pair(from, to) : std::pair(0, 0);
}

bool LeafRenderer::RenderMixed(const LeafWindow& leaf, Image& image) {
  bool flat = true;
  for (int p : leaf.polygons) {
    if (geo_.polygons[p].transparent) return RenderMixedTransparent(leaf, image);
    flat = flat && shader_.IsFlat(p);
  }
  const PixelRect& r = leaf.rect;
  PrefetchPixels(r, image);
  if (flat) {  // each polygon's colour, by its slot
    if (slot_of_.size() < geo_.polygons.size()) slot_of_.assign(geo_.polygons.size(), -1);
    flat_colours_.clear();
    for (int p : leaf.polygons) {
      slot_of_[p] = static_cast<int>(flat_colours_.size());
      flat_colours_.push_back(shader_.FlatColour(p));
    }
  }
  const bool flat_box = flat && !shape_.needs_moments;
  const bool computed = ComputeCells(r, leaf.polygons, /*colour_sums=*/flat_box);
  if (computed && flat_box) RenderFlatBox(r, image);
  if (flat && (flat_box || !computed))
    for (int p : leaf.polygons) slot_of_[p] = -1;  // ready for the next leaf
  if (!computed) return false;
  if (flat_box) return true;

  // Each pixel's polygons and weights (its entries), in the order the colours are summed. A leaf
  // of flat-coloured polygons finishes each pixel at once; any other keeps every pixel's entries,
  // shades them in batches by polygon, then sums them.
  const int span = shape_.cells_per_axis - 1;
  const Rgba open_sky{sky_.r, sky_.g, sky_.b, PixelAlpha(0, 1)};  // a pixel nothing reaches
  entries_.clear();
  if (!flat) pixel_begin_.resize(static_cast<size_t>(r.width()) * r.height() + 1);
  for (int py = 0; py < r.height(); ++py) {
    const auto [from, to] = ReachedPixels(py, span, r.width());
    Rgba* row = &Pixel(image, r.x0, r.y0 + py);
    size_t* begins = flat ? nullptr : &pixel_begin_[static_cast<size_t>(py) * r.width()];
    if (flat) {
      std::fill(row, row + from, open_sky);
      std::fill(row + to, row + r.width(), open_sky);
    } else {
      std::fill(begins, begins + from, entries_.size());
    }
    for (int px = from; px < to; ++px) {
      const size_t first = entries_.size();
      GatherPixel(px, py);
      if (!flat) {
        begins[px] = first;
        continue;
      }
      row[px] =
          first == entries_.size() ? open_sky : PixelValue(first, entries_.size(), [&](size_t e) {
            return flat_colours_[slot_of_[entries_[e].polygon]];
          });
      entries_.resize(first);
    }
    if (!flat) std::fill(begins + to, begins + r.width(), entries_.size());
  }
  if (flat) {
    for (int p : leaf.polygons) slot_of_[p] = -1;  // ready for the next leaf
    return true;
  }
  pixel_begin_.back() = entries_.size();

  ShadeEntries(r);
  for (int py = 0; py < r.height(); ++py) {
    Rgba* row = &Pixel(image, r.x0, r.y0 + py);
    for (int px = 0; px < r.width(); ++px) {
      const size_t pixel = static_cast<size_t>(py) * r.width() + px;
      const size_t first = pixel_begin_[pixel], last = pixel_begin_[pixel + 1];
      row[px] =
          first == last ? open_sky : PixelValue(first, last, [&](size_t e) { return colours_[e]; });
    }
  }
  return true;
}

// Under a box filter every cell of a pixel's aperture weighs the same, so a flat-coloured leaf's
// pixel is the box's scale times the sum of its cells' colours by area: each cell is summed once
// (not once for each of the pixels that weigh it) and no pixel merges its pieces by polygon. The
// sums are the merged ones, taken in another order (in double, not float): pixels agree with
// the merging path to rounding.
void LeafRenderer::RenderFlatBox(const PixelRect& r, Image& image) {
  const double scale = CellWeight(aa_, {1, 0, 0, 0}, 0, 0);
  const int span = shape_.cells_per_axis - 1;
  // Each row's cells summed with their right neighbours once (box2), shared by the two rows of
  // pixels that weigh them.
  auto add = [](const CellSum& a, const CellSum& b) {
    return CellSum{a.r + b.r, a.g + b.g, a.b + b.b, a.area + b.area};
  };
  if (span == 1) {
    pair_sums_.resize(static_cast<size_t>(nx_) * (r.height() + 1));
    for (int j = 0; j <= r.height(); ++j) {
      const CellSum* cells = &cell_sums_[static_cast<size_t>(j) * nx_];
      CellSum* pairs = &pair_sums_[static_cast<size_t>(j) * nx_];
      for (int i = 0; i < r.width(); ++i) pairs[i] = add(cells[i], cells[i + 1]);
    }
  }
  const std::vector<CellSum>& rows = span == 1 ? pair_sums_ : cell_sums_;
  for (int py = 0; py < r.height(); ++py) {
    Rgba* row = &Pixel(image, r.x0, r.y0 + py);
    const CellSum* upper = &rows[static_cast<size_t>(py) * nx_];
    const CellSum* lower = &rows[static_cast<size_t>(py + span) * nx_];
    for (int px = 0; px < r.width(); ++px) {
      const CellSum sum = span == 1 ? add(upper[px], lower[px]) : upper[px];
      const double total = scale * sum.area;
      const float sky_w = static_cast<float>(std::max(0.0, 1.0 - total));
      row[px] = {static_cast<float>(scale * sum.r) + sky_.r * sky_w,
                 static_cast<float>(scale * sum.g) + sky_.g * sky_w,
                 static_cast<float>(scale * sum.b) + sky_.b * sky_w, PixelAlpha(total, sky_w)};
    }
  }
}

LeafRenderer::CellSum LeafRenderer::ColourSum(size_t first) const {
  CellSum sum{0, 0, 0, 0};
  for (size_t k = first; k < pieces_.size(); ++k) {
    const Rgba& colour = flat_colours_[slot_of_[pieces_[k].polygon]];
    const double area = pieces_[k].moments.area;
    sum.r += colour.r * area, sum.g += colour.g * area, sum.b += colour.b * area;
    sum.area += area;
  }
  return sum;
}

bool LeafRenderer::ComputeCells(const PixelRect& r, std::span<const int> polygons,
                                bool colour_sums) {
  const int span = shape_.cells_per_axis - 1;  // extra cells beyond the pixels
  nx_ = r.width() + span;
  const int ny = r.height() + span;
  pieces_.clear();
  if (colour_sums) cell_sums_.assign(static_cast<size_t>(nx_) * ny, CellSum{0, 0, 0, 0});
  cell_begin_.assign(static_cast<size_t>(nx_) * ny + 1, 0);
  reached_from_.assign(ny, nx_);
  reached_to_.assign(ny, 0);
  // The leaf's polygons nearest first (CellCoverage::Compute stops its scan of a cell at the
  // first one behind a whole-cell cover), each by the largest inverse depth over its vertices.
  if (nearest_.size() < geo_.polygons.size()) nearest_.resize(geo_.polygons.size());
  // Nearest first by the nearest values' leading 30 bits (a tie in them is a tie of depth within
  // about the coplanar tolerance), ties drawn last first: under a stack of coplanar layers the
  // first whole-cell cover a cell's scan meets is the layer drawn over the rest, which hides them.
  if (draw_order_.size() < geo_.polygons.size()) draw_order_.resize(geo_.polygons.size());
  keys_.clear();
  for (int p : polygons) {
    const ScreenPolygon& polygon = geo_.polygons[p];
    double w = -INFINITY;
    for (const Vec2& v : polygon.vertices) w = std::max(w, polygon.inv_depth.At(v.x, v.y));
    nearest_[p] = w;
    draw_order_[p] = DrawOrder(polygon.layer, p);
    keys_.push_back({NearestQuantum(w), draw_order_[p], p});
  }
  std::sort(keys_.begin(), keys_.end(), [](const DepthKey& a, const DepthKey& b) {
    return a.quantum > b.quantum || (a.quantum == b.quantum && a.order > b.order);
  });
  SortedWithoutHiddenCopies();
  if (!HoldMemory()) return false;
  // The lists may take what the budget has left and the room they hold already.
  const size_t room_bytes = memory_ ? memory_->Room() : SIZE_MAX;
  const size_t room =
      room_bytes == SIZE_MAX ? SIZE_MAX : (room_bytes + bins_.ItemBytes()) / sizeof(int);
  if (!bins_.Build(geo_.polygons, by_depth_, r.x0, r.y0, shape_.cell_offset, nx_, ny, room)) {
    memory_->Refuse("a leaf's lists of polygons by cell", bins_.NeededItemBytes());
    return false;
  }
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx_; ++i) {
      const size_t before = pieces_.size();
      cell_begin_[static_cast<size_t>(j) * nx_ + i] = before;
      if (bins_.Cell(i, j).empty()) {  // nothing reaches it (most of a sparse frame)
        if (surfaces_ != nullptr && OwnsCell(r, r.x0 + i, r.y0 + j) &&
            surfaces_->Wanted(r.x0 + i, r.y0 + j))
          writer_->Record(r.x0 + i, r.y0 + j, 0, [](size_t) { return 0; });
        continue;
      }
      const double cx = r.x0 + i + shape_.cell_offset + 0.5;
      const double cy = r.y0 + j + shape_.cell_offset + 0.5;
      coverage_.Compute(geo_.polygons, bins_.Cell(i, j), nearest_, draw_order_, cx, cy,
                        shape_.needs_moments, pieces_);
      if (coverage_.Stopped()) return false;
      if (surfaces_ != nullptr && OwnsCell(r, r.x0 + i, r.y0 + j) &&
          surfaces_->Wanted(r.x0 + i, r.y0 + j))
        RecordCellSurfaces(r.x0 + i, r.y0 + j, before);
      if (colour_sums) {  // the cell's pieces are summed at once, not kept
        cell_sums_[static_cast<size_t>(j) * nx_ + i] = ColourSum(before);
        pieces_.resize(before);
        continue;
      }
      if (pieces_.size() > before) {
        reached_from_[j] = std::min(reached_from_[j], i);
        reached_to_[j] = i + 1;
      }
    }
    if ((stop_ && stop_()) || !HoldMemory()) return false;
  }
  cell_begin_.back() = pieces_.size();
  return true;
}

// Identical polygons have equal nearest values, so copies lie in runs of one quantum in keys_ (a
// run of one, most of a frame, costs a comparison). In a longer run, the polygons identical to one
// drawn over them are hidden by it wherever they are (the leaf is opaque) and leave the leaf's
// list: ten thousand copies cost one polygon's cells.
void LeafRenderer::SortedWithoutHiddenCopies() {
  by_depth_.clear();
  for (size_t i = 0; i < keys_.size();) {
    size_t end = i + 1;
    while (end < keys_.size() && keys_[end].quantum == keys_[i].quantum) ++end;
    if (end - i == 1) {
      by_depth_.push_back(keys_[i].polygon);
      i = end;
      continue;
    }
    // The run by hash, each hash's polygons drawn last first; then back in the run's order.
    copies_.clear();
    for (size_t k = i; k < end; ++k)
      copies_.push_back({ScreenPolygonHash(geo_.polygons[keys_[k].polygon]), keys_[k].polygon});
    auto order = [&](int p) { return draw_order_[p]; };
    std::sort(copies_.begin(), copies_.end(), [&](const auto& a, const auto& b) {
      return a.first < b.first || (a.first == b.first && order(a.second) > order(b.second));
    });
    size_t unique = 0;
    for (size_t k = 0; k < copies_.size(); ++k) {
      const bool hidden = unique > 0 && copies_[unique - 1].first == copies_[k].first &&
                          SameScreenPolygon(geo_.polygons[copies_[unique - 1].second],
                                            geo_.polygons[copies_[k].second]);
      if (!hidden) copies_[unique++] = copies_[k];
    }
    std::sort(copies_.begin(), copies_.begin() + static_cast<long>(unique),
              [&](const auto& a, const auto& b) { return order(a.second) > order(b.second); });
    for (size_t k = 0; k < unique; ++k) by_depth_.push_back(copies_[k].second);
    i = end;
  }
}

size_t LeafRenderer::WorkingBytes() const {
  return coverage_.WorkingBytes() + bins_.WorkingBytes() +
         HeldBytes(pieces_, nearest_, draw_order_, keys_, by_depth_, copies_, cell_begin_,
                   reached_from_, reached_to_, entries_, pixel_begin_, order_, group_begin_, slots_,
                   slot_of_, points_, batch_, colours_, flat_colours_, cell_sums_, pair_sums_,
                   passes_, layers_, cell_layers_, candidates_, needed_, layer_begin_) +
         HeldMapBytes(pixel_entry_);
}

void LeafRenderer::GatherPixel(int px, int py) {
  const int span = shape_.cells_per_axis - 1;
  const size_t nx = nx_;
  // A box filter's weight is the area times a constant (CellWeight's, the same product).
  const bool box = !shape_.needs_moments;
  const double box_scale = CellWeight(aa_, {1, 0, 0, 0}, 0, 0);
  if (span == 0 && box) {  // box1: the pixel's one cell, whose pieces are distinct polygons
    const size_t cell = static_cast<size_t>(py) * nx + px;
    for (size_t k = cell_begin_[cell]; k < cell_begin_[cell + 1]; ++k)
      entries_.push_back({pieces_[k].polygon, Coordinate(px), Coordinate(py),
                          box_scale * pieces_[k].moments.area});
    return;
  }
  size_t pieces = 0;
  for (int cy = 0; cy <= span; ++cy) {
    const size_t row = static_cast<size_t>(py + cy) * nx + px;
    pieces += cell_begin_[row + span + 1] - cell_begin_[row];
  }
  if (pieces == 0) return;  // the sky
  if (pieces == 4 && span == 1 && box) {
    // Most pixels of a box2 leaf: each of the four cells holds one piece, of one polygon
    // (inside it, or beside an edge to the sky). The sum is the general loop's, in its order.
    const size_t c00 = static_cast<size_t>(py) * nx + px, c01 = c00 + nx;
    const size_t k00 = cell_begin_[c00], k10 = cell_begin_[c00 + 1];
    const size_t k01 = cell_begin_[c01], k11 = cell_begin_[c01 + 1];
    const int polygon = pieces_[k00].polygon;
    if (k10 - k00 == 1 && cell_begin_[c00 + 2] - k10 == 1 && k11 - k01 == 1 &&
        pieces_[k10].polygon == polygon && pieces_[k01].polygon == polygon &&
        pieces_[k11].polygon == polygon) {
      double w = box_scale * pieces_[k00].moments.area;
      w += box_scale * pieces_[k10].moments.area;
      w += box_scale * pieces_[k01].moments.area;
      w += box_scale * pieces_[k11].moments.area;
      entries_.push_back({polygon, Coordinate(px), Coordinate(py), w});
      return;
    }
  }
  // A pixel's pieces are few but for crowded cells (a whole scene in one pixel).
  if (pieces <= kCrowdedPixelPieces) {
    // Merged in a local array without branches on the data (which polygon repeats varies from
    // pixel to pixel): each piece takes a new slot, or the slot of its polygon when it has one;
    // a new slot's weight starts at 0, and 0 + w is w, so the sums are the same as adding to a
    // found entry.
    Weighted merged[kCrowdedPixelPieces];
    size_t count = 0;
    for (int cy = 0; cy <= span; ++cy) {
      for (int cx = 0; cx <= span; ++cx) {
        const size_t cell = static_cast<size_t>(py + cy) * nx + (px + cx);
        for (size_t k = cell_begin_[cell]; k < cell_begin_[cell + 1]; ++k) {
          const double w = box ? box_scale * pieces_[k].moments.area
                               : CellWeight(aa_, pieces_[k].moments, cx, cy);
          const int polygon = pieces_[k].polygon;
          merged[count] = {polygon, Coordinate(px), Coordinate(py), 0};
          size_t e = count;
          for (size_t j = 0; j < count; ++j) e = merged[j].polygon == polygon ? j : e;
          merged[e].weight += w;
          count += e == count;
        }
      }
    }
    entries_.insert(entries_.end(), merged, merged + count);
    return;
  }
  // A crowded pixel: its polygons found through a map.
  pixel_entry_.clear();
  for (int cy = 0; cy <= span; ++cy) {
    for (int cx = 0; cx <= span; ++cx) {
      const size_t cell = static_cast<size_t>(py + cy) * nx + (px + cx);
      for (size_t k = cell_begin_[cell]; k < cell_begin_[cell + 1]; ++k) {
        const double w =
            box ? box_scale * pieces_[k].moments.area : CellWeight(aa_, pieces_[k].moments, cx, cy);
        const int polygon = pieces_[k].polygon;
        const auto [it, added] = pixel_entry_.try_emplace(polygon, entries_.size());
        if (added)
          entries_.push_back({polygon, Coordinate(px), Coordinate(py), w});
        else
          entries_[it->second].weight += w;
      }
    }
  }
}

void LeafRenderer::TransparentLayers(const LeafWindow& leaf, double cx, double cy) {
  layers_.clear();
  for (int p : leaf.polygons) {
    const ScreenPolygon& polygon = geo_.polygons[p];
    if (polygon.transparent && PolygonOverlapsRect(polygon, cx - 0.5, cy - 0.5, cx + 0.5, cy + 0.5))
      layers_.push_back(p);
  }
  if (layers_.size() <= kMaxLayers) return;
  std::stable_sort(layers_.begin(), layers_.end(), [&](int a, int b) {
    return geo_.polygons[a].inv_depth.At(cx, cy) > geo_.polygons[b].inv_depth.At(cx, cy);
  });
  layers_.resize(kMaxLayers);
}

// Compositing is linear in each layer's alpha. With alpha taken at the pixel centre (as the
// colour is, seed 002), the pixel composited over a transparent polygon T equals
//   alpha_T * (the pixel with T opaque) + (1 - alpha_T) * (the pixel without T),
// point by point and so for the filtered pixel. Over the k layers of a cell this is a sum over
// the 2^k subsets of layers drawn opaque, each an exact visibility pass of CellCoverage, weighted
// by the product of alpha (layers in the subset) and 1 - alpha (the others) at each pixel.
bool LeafRenderer::RenderMixedTransparent(const LeafWindow& leaf, Image& image) {
  const PixelRect& r = leaf.rect;
  if (surfaces_ != nullptr) RecordWindowSurfaces(r, -2);  // what shows through is not recorded
  const int span = shape_.cells_per_axis - 1;
  const int nx = r.width() + span, ny = r.height() + span;
  const size_t cells = static_cast<size_t>(nx) * ny;
  auto cell_x = [&](int i) { return r.x0 + i + shape_.cell_offset + 0.5; };
  auto cell_y = [&](int j) { return r.y0 + j + shape_.cell_offset + 0.5; };

  // Each cell's transparent layers.
  cell_layers_.clear();
  layer_begin_.assign(cells + 1, 0);
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      layer_begin_[static_cast<size_t>(j) * nx + i] = cell_layers_.size();
      TransparentLayers(leaf, cell_x(i), cell_y(j));
      cell_layers_.insert(cell_layers_.end(), layers_.begin(), layers_.end());
    }
  }
  layer_begin_[cells] = cell_layers_.size();
  // Each pixel's entries: the layers of its cells, and with `pieces` every polygon of their passes.
  auto collect_entries = [&](bool pieces) {
    entries_.clear();
    pixel_begin_.clear();
    for (int py = 0; py < r.height(); ++py) {
      for (int px = 0; px < r.width(); ++px) {
        pixel_begin_.push_back(entries_.size());
        pixel_entry_.clear();
        auto add = [&](int polygon) {
          if (pixel_entry_.try_emplace(polygon, entries_.size()).second)
            entries_.push_back({polygon, Coordinate(px), Coordinate(py), 0});
        };
        for (int cy = 0; cy <= span; ++cy) {
          for (int cx = 0; cx <= span; ++cx) {
            const size_t cell = static_cast<size_t>(py + cy) * nx + (px + cx);
            for (size_t k = layer_begin_[cell]; k < layer_begin_[cell + 1]; ++k)
              add(cell_layers_[k]);
            if (!pieces) continue;
            const size_t pieces_begin = passes_[cell_begin_[cell]].begin;
            const size_t pieces_end = passes_[cell_begin_[cell + 1] - 1].end;
            for (size_t k = pieces_begin; k < pieces_end; ++k) add(pieces_[k].polygon);
          }
        }
      }
    }
    pixel_begin_.push_back(entries_.size());
  };

  // The layers' alpha at every pixel they reach decides which subsets of a cell's layers carry
  // weight there: a layer of alpha 1 is in every such subset, one of alpha 0 (a MASK cut-out, or
  // a BLEND texel left clear) in none. Only the subsets some pixel of the cell weighs are
  // visibility passes: a cell under MASK layers alone needs at most one pass per pixel it feeds,
  // not 2^k. The passes left out would have weighed 0 everywhere: the pixels are unchanged.
  collect_entries(false);
  ShadeEntries(r);
  needed_.assign(cells, 0);
  for (int py = 0; py < r.height(); ++py) {
    for (int px = 0; px < r.width(); ++px) {
      const size_t pixel = static_cast<size_t>(py) * r.width() + px;
      for (int cy = 0; cy <= span; ++cy) {
        for (int cx = 0; cx <= span; ++cx) {
          const size_t cell = static_cast<size_t>(py + cy) * nx + (px + cx);
          unsigned opaque = 0, open = 0;  // layers of alpha 1, layers of alpha in (0, 1)
          for (size_t k = layer_begin_[cell]; k < layer_begin_[cell + 1]; ++k) {
            size_t e = pixel_begin_[pixel];
            while (entries_[e].polygon != cell_layers_[k]) ++e;
            const float alpha = colours_[e].a;
            const unsigned bit = 1u << (k - layer_begin_[cell]);
            if (alpha >= 1.0f) opaque |= bit;
            if (alpha > 0.0f && alpha < 1.0f) open |= bit;
          }
          // Every subset of the open layers, with the opaque ones.
          for (unsigned sub = open;; sub = (sub - 1) & open) {
            needed_[cell] |= 1u << (opaque | sub);
            if (sub == 0) break;
          }
        }
      }
    }
  }

  pieces_.clear();
  passes_.clear();
  cell_begin_.assign(cells + 1, 0);
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const size_t cell = static_cast<size_t>(j) * nx + i;
      cell_begin_[cell] = passes_.size();
      const int* layers = cell_layers_.data() + layer_begin_[cell];
      const size_t count = layer_begin_[cell + 1] - layer_begin_[cell];
      for (unsigned included = 0; included < (1u << count); ++included) {
        if (!(needed_[cell] >> included & 1u)) continue;
        candidates_.clear();
        for (int p : leaf.polygons) {
          const int* at = std::find(layers, layers + count, p);
          if (at == layers + count || (included >> (at - layers) & 1u)) candidates_.push_back(p);
        }
        const size_t begin = pieces_.size();
        coverage_.Compute(geo_.polygons, candidates_, cell_x(i), cell_y(j), shape_.needs_moments,
                          pieces_);
        if (coverage_.Stopped()) return false;
        passes_.push_back({included, begin, pieces_.size()});
      }
    }
    if ((stop_ && stop_()) || !HoldMemory()) return false;
  }
  cell_begin_[cells] = passes_.size();

  // Every polygon a pixel needs the colour and alpha of: its cells' pieces and layers.
  collect_entries(true);
  ShadeEntries(r);

  for (int py = 0; py < r.height(); ++py) {
    for (int px = 0; px < r.width(); ++px) {
      const size_t pixel = static_cast<size_t>(py) * r.width() + px;
      const size_t first = pixel_begin_[pixel], last = pixel_begin_[pixel + 1];
      const bool crowded = last - first > kCrowdedPixelPieces;
      if (crowded) {
        pixel_entry_.clear();
        for (size_t e = first; e < last; ++e) pixel_entry_.emplace(entries_[e].polygon, e);
      }
      auto colour_of = [&](int polygon) -> const Rgba& {  // every polygon asked has an entry
        if (crowded) return colours_[pixel_entry_.at(polygon)];
        size_t e = first;
        while (e + 1 < last && entries_[e].polygon != polygon) ++e;
        return colours_[e];
      };
      double r_sum = 0, g_sum = 0, b_sum = 0, total = 0;
      for (int cy = 0; cy <= span; ++cy) {
        for (int cx = 0; cx <= span; ++cx) {
          const size_t cell = static_cast<size_t>(py + cy) * nx + (px + cx);
          float alpha[kMaxLayers];
          const size_t layers = layer_begin_[cell + 1] - layer_begin_[cell];
          for (size_t k = 0; k < layers; ++k)
            alpha[k] = colour_of(cell_layers_[layer_begin_[cell] + k]).a;
          for (size_t g = cell_begin_[cell]; g < cell_begin_[cell + 1]; ++g) {
            const Pass& pass = passes_[g];
            double weight = 1;
            for (size_t k = 0; k < layers; ++k)
              weight *= (pass.included >> k & 1u) ? alpha[k] : 1.0 - alpha[k];
            if (weight == 0) continue;
            for (size_t k = pass.begin; k < pass.end; ++k) {
              const double w = weight * CellWeight(aa_, pieces_[k].moments, cx, cy);
              const Rgba& c = colour_of(pieces_[k].polygon);
              r_sum += c.r * w, g_sum += c.g * w, b_sum += c.b * w;
              total += w;
            }
          }
        }
      }
      const float sky_w = static_cast<float>(std::max(0.0, 1.0 - total));
      Pixel(image, r.x0 + px, r.y0 + py) = {
          static_cast<float>(r_sum) + sky_.r * sky_w, static_cast<float>(g_sum) + sky_.g * sky_w,
          static_cast<float>(b_sum) + sky_.b * sky_w, PixelAlpha(total, sky_w)};
    }
  }
  return true;
}

}  // namespace aperture
