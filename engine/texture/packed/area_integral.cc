#include "texture/packed/area_integral.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <memory>

namespace aperture::packed {
namespace {

std::array<uint64_t, 4> Scaled(uint32_t colour, uint64_t count) {
  return {Channel(colour, 0) * count, Channel(colour, 1) * count, Channel(colour, 2) * count,
          Channel(colour, 3) * count};
}
void Add(std::array<uint64_t, 4>& a, const std::array<uint64_t, 4>& b) {
  for (int c = 0; c < 4; ++c) a[c] += b[c];
}

// One axis of a rectangle, reduced to the texture period [0, n): pieces [lo, hi) with 0 <= lo <
// hi <= n, each taken `times` times.
struct Piece {
  double lo, hi, times;
};
int SplitPeriodic(double a, double b, double n, Piece out[3]) {
  int count = 0;
  if (!(b > a)) return 0;
  const double shift = std::floor(a / n) * n;
  a -= shift;
  b -= shift;
  if (a >= n) {  // rounding of a / n
    a -= n;
    b -= n;
  }
  if (a < 0) a = 0;
  if (b <= n) {
    out[count++] = {a, b, 1};
    return count;
  }
  if (a < n) out[count++] = {a, n, 1};
  const double rest = b - n;
  const double periods = std::floor(rest / n);
  if (periods > 0) out[count++] = {0, n, periods};
  const double tail = rest - periods * n;
  if (tail > 0) out[count++] = {0, std::min(tail, n), 1};
  return count;
}

// The last texel a coordinate range [lo, hi) reaches (hi > 0).
uint32_t LastTexel(double hi) { return static_cast<uint32_t>(std::ceil(hi) - 1); }

}  // namespace

AreaIntegrator::AreaIntegrator(const PackedTextureView& texture) : texture_(texture) {
  static std::atomic<uint64_t> next_id{1};
  id_ = next_id.fetch_add(1, std::memory_order_relaxed);
  const auto steps = texture.steps();
  const auto indices = texture.indices();
  const auto palette = texture.palette();
  prefix_.resize(steps.size() + 1);
  int64_t previous = -1;
  for (size_t i = 0; i < steps.size(); ++i) {
    prefix_[i + 1] = prefix_[i];
    Add(prefix_[i + 1], Scaled(palette[indices[i]], static_cast<uint64_t>(steps[i] - previous)));
    previous = steps[i];
  }
  total_ = SumTexels(0, 0, texture.width(), texture.height());
}

std::array<uint64_t, 4> AreaIntegrator::SumSteps(uint32_t first, uint32_t last) const {
  return SumStepsInRuns(first, last, texture_.RunOfStep(first), texture_.RunOfStep(last));
}

std::array<uint64_t, 4> AreaIntegrator::SumStepsInRuns(uint32_t first, uint32_t last, size_t a,
                                                       size_t b) const {
  const auto steps = texture_.steps();
  const auto palette = texture_.palette();
  const auto indices = texture_.indices();
  if (a == b) return Scaled(palette[indices[a]], uint64_t{last} - first + 1);
  std::array<uint64_t, 4> sum = Scaled(palette[indices[a]], uint64_t{steps[a]} - first + 1);
  for (int c = 0; c < 4; ++c) sum[c] += prefix_[b][c] - prefix_[a + 1][c];
  Add(sum, Scaled(palette[indices[b]], uint64_t{last} - steps[b - 1]));
  return sum;
}

size_t AreaIntegrator::RunIn(size_t lo, size_t hi, uint64_t step) const {
  // First run in [lo, hi] ending at or after `step` (the answer is known to lie there).
  const auto steps = texture_.steps();
  if (step > steps.back()) return hi;
  return static_cast<size_t>(
      std::lower_bound(steps.begin() + lo, steps.begin() + hi + 1, static_cast<uint32_t>(step)) -
      steps.begin());
}

// A thread's recent answers to "where is this block on the curve and which runs hold it", per
// integrator: neighbouring pixels' footprints visit mostly the same blocks, and a block's place
// and runs are functions of the block (the airport's frame, whose ground is a packed map: 60.3 ->
// 50.1 ms at 2 threads). Entries are tagged with the integrator's id, never its address, which a
// later integrator may reuse.
struct AreaIntegrator::BlockCache {
  struct Entry {
    uint64_t owner = 0;  // 0: empty (ids start at 1)
    uint64_t key = 0;
    uint64_t step0 = 0;
    size_t run_lo = 0, run_hi = 0;
    uint32_t state = 0;
  };
  static constexpr size_t kEntries = 16384;  // 768 KiB a thread, from the heap
  static uint64_t Key(const Block& b) {
    return (uint64_t{b.x} << 34) | (uint64_t{b.y} << 6) | static_cast<uint64_t>(b.level);
  }
  static bool Holds(const Entry& e, uint64_t owner, const Block& b) {
    return e.owner == owner && e.key == Key(b);
  }
  static Entry EntryOf(uint64_t owner, const Block& b) {
    return {owner, Key(b), b.step0, b.run_lo, b.run_hi, b.state};
  }
  static Entry& Of(const Block& b) {
    static thread_local std::unique_ptr<Entry[]> entries;
    if (!entries) entries = std::make_unique<Entry[]>(kEntries);
    return entries[(b.x * 73856093u ^ b.y * 19349663u ^ static_cast<uint32_t>(b.level)) &
                   (kEntries - 1)];
  }
};

AreaIntegrator::Block AreaIntegrator::Enclosing(uint32_t x0, uint32_t y0, uint32_t x1,
                                                uint32_t y1) const {
  // The lowest level at which both corners fall in one block: above the highest differing bit.
  const int level =
      std::min(texture_.order(), static_cast<int>(std::bit_width((x0 ^ x1) | (y0 ^ y1))));
  const uint32_t above = level >= 32 ? 0 : ~0u << level;  // the block's bits of a coordinate
  Block b{level, x0 & above, y0 & above, 0, 0, 0, 0};
  // Neighbouring pixels' footprints mostly start at the same block: all of it from the thread's
  // last answers for this integrator, or walked to and searched, and kept there.
  BlockCache::Entry& entry = BlockCache::Of(b);
  if (BlockCache::Holds(entry, id_, b)) {
    b.state = entry.state;
    b.step0 = entry.step0;
    b.run_lo = entry.run_lo;
    b.run_hi = entry.run_hi;
    return b;
  }
  // Walk down the curve to that block: orientation and first step.
  b = {texture_.order(), 0, 0, 0, 0, 0, 0};
  while (b.level > level) {
    const int half = b.level - 1;
    const uint32_t xb = (x0 >> half) & 1u, yb = (y0 >> half) & 1u;
    uint32_t digit = xb | (yb << 1);
    if (texture_.curve() == Curve::kHilbert) {
      digit = kHilbertDigits.digit[b.state][yb * 2 + xb];
      b.state = HilbertChildOf(b.state, digit).state;
    }
    b.step0 += uint64_t{digit} << (2 * half);
    b.x += xb << half;
    b.y += yb << half;
    b.level = half;
  }
  SetRuns(b);
  entry = BlockCache::EntryOf(id_, b);
  return b;
}

void AreaIntegrator::SetRuns(Block& b) const {
  const uint64_t last =
      std::min<uint64_t>(b.step0 + (uint64_t{1} << (2 * b.level)) - 1, texture_.steps().back());
  uint32_t lo, hi;
  const uint64_t side = uint64_t{1} << b.level;
  if (index_ != nullptr && b.x + side <= texture_.width() && b.y + side <= texture_.height() &&
      index_->RunsAround(b.x, b.y, b.level, lo, hi)) {
    b.run_lo = RunIn(lo, hi, b.step0);
    b.run_hi = RunIn(b.run_lo, hi, last);
    return;
  }
  b.run_lo = texture_.RunOfStep(static_cast<uint32_t>(b.step0));
  b.run_hi = texture_.RunOfStep(static_cast<uint32_t>(last));
}

AreaIntegrator::Block AreaIntegrator::Child(const Block& b, uint32_t digit) const {
  const int half = b.level - 1;
  const auto [xb, yb, child] = ChildQuadrant(texture_.curve(), b.state, digit);
  Block o;
  o.level = half;
  o.x = b.x + (xb << half);
  o.y = b.y + (yb << half);
  o.state = child;
  o.step0 = b.step0 + digit * (uint64_t{1} << (2 * half));
  o.run_lo = o.run_hi = 0;
  return o;
}

void AreaIntegrator::FindRuns(const Block& parent, Block& o) const {
  const uint64_t side = uint64_t{1} << o.level;
  const bool inside = o.x + side <= texture_.width() && o.y + side <= texture_.height();
  BlockCache::Entry* entry = nullptr;
  if (inside) {
    entry = &BlockCache::Of(o);
    if (BlockCache::Holds(*entry, id_, o)) {
      o.run_lo = entry->run_lo;
      o.run_hi = entry->run_hi;
      return;
    }
  }
  FindRunsBySearch(parent, o);
  if (entry != nullptr) *entry = BlockCache::EntryOf(id_, o);
}

void AreaIntegrator::FindRunsBySearch(const Block& parent, Block& o) const {
  const uint64_t steps = uint64_t{1} << (2 * o.level);
  o.run_lo = o.x < texture_.width() && o.y < texture_.height()
                 ? RunIn(parent.run_lo, parent.run_hi, o.step0)
                 : parent.run_hi;
  o.run_hi = RunIn(o.run_lo, parent.run_hi, o.step0 + steps - 1);
}

void AreaIntegrator::Children(const Block& b, Block out[4]) const {
  for (uint32_t digit = 0; digit < 4; ++digit) {
    out[digit] = Child(b, digit);
    FindRuns(b, out[digit]);
  }
}

std::array<uint64_t, 4> AreaIntegrator::SumBlock(const Block& b, uint32_t x0, uint32_t y0,
                                                 uint32_t x1, uint32_t y1) const {
  const uint64_t size = uint64_t{1} << b.level;
  const uint64_t ix0 = std::max<uint64_t>(b.x, x0), ix1 = std::min<uint64_t>(b.x + size, x1);
  const uint64_t iy0 = std::max<uint64_t>(b.y, y0), iy1 = std::min<uint64_t>(b.y + size, y1);
  if (ix0 >= ix1 || iy0 >= iy1) return {};
  // A block inside one run has a single colour.
  if (b.run_lo == b.run_hi)
    return Scaled(texture_.palette()[texture_.indices()[b.run_lo]], (ix1 - ix0) * (iy1 - iy0));
  if (ix1 - ix0 == size && iy1 - iy0 == size)  // whole block: one contiguous step range
    return SumStepsInRuns(static_cast<uint32_t>(b.step0),
                          static_cast<uint32_t>(b.step0 + size * size - 1), b.run_lo, b.run_hi);
  Block children[4];
  Children(b, children);
  std::array<uint64_t, 4> sum{};
  for (const Block& c : children) Add(sum, SumBlock(c, x0, y0, x1, y1));
  return sum;
}

std::array<uint64_t, 4> AreaIntegrator::SumTexels(uint32_t x0, uint32_t y0, uint32_t x1,
                                                  uint32_t y1) const {
  x1 = std::min(x1, texture_.width());
  y1 = std::min(y1, texture_.height());
  if (x0 >= x1 || y0 >= y1) return {};
  return SumBlock(Enclosing(x0, y0, x1 - 1, y1 - 1), x0, y0, x1, y1);
}

void AreaIntegrator::IntegrateBlock(const Block& b, double x0, double y0, double x1, double y1,
                                    std::array<double, 4>& sum) const {
  const double size = static_cast<double>(uint64_t{1} << b.level);
  const double ix0 = std::max<double>(b.x, x0), ix1 = std::min<double>(b.x + size, x1);
  const double iy0 = std::max<double>(b.y, y0), iy1 = std::min<double>(b.y + size, y1);
  if (ix0 >= ix1 || iy0 >= iy1) return;
  if (b.run_lo == b.run_hi) {  // one colour: colour x overlap area, fractional edges included
    AddRunColour(b.run_lo, (ix1 - ix0) * (iy1 - iy0), sum);
    return;
  }
  if (ix1 - ix0 == size && iy1 - iy0 == size) {  // whole block, every texel fully covered
    const uint64_t n = uint64_t{1} << (2 * b.level);
    const auto s = SumStepsInRuns(static_cast<uint32_t>(b.step0),
                                  static_cast<uint32_t>(b.step0 + n - 1), b.run_lo, b.run_hi);
    for (int c = 0; c < 4; ++c) sum[c] += static_cast<double>(s[c]);
    return;
  }
  // The children the rectangle reaches, by the test IntegrateBlock makes first, before their run
  // searches: an edge of the rectangle mostly passes through two of the four.
  const double half = size / 2;
  for (uint32_t digit = 0; digit < 4; ++digit) {
    Block c = Child(b, digit);
    if (std::max<double>(c.x, x0) >= std::min<double>(c.x + half, x1) ||
        std::max<double>(c.y, y0) >= std::min<double>(c.y + half, y1))
      continue;
    FindRuns(b, c);
    IntegrateBlock(c, x0, y0, x1, y1, sum);
  }
}

bool AreaIntegrator::IntegrateOverCells(double x0, double y0, double x1, double y1,
                                        std::array<double, 4>& sum) const {
  if (index_ == nullptr) return false;
  const int bits = index_->cell_bits();
  const uint32_t columns = (LastTexel(x1) >> bits) - (static_cast<uint32_t>(x0) >> bits) + 1;
  const uint32_t rows = (LastTexel(y1) >> bits) - (static_cast<uint32_t>(y0) >> bits) + 1;
  if (columns * rows > kMaxCells) return false;
  IntegrateOverBlocks(bits, x0, y0, x1, y1, sum);
  return true;
}

void AreaIntegrator::IntegrateOverBlocks(int level, double x0, double y0, double x1, double y1,
                                         std::array<double, 4>& sum) const {
  const double side = static_cast<double>(uint32_t{1} << level);
  for (uint32_t by = static_cast<uint32_t>(y0) >> level; by <= LastTexel(y1) >> level; ++by) {
    const double ry0 = std::max(y0, by * side), ry1 = std::min(y1, (by + 1) * side);
    for (uint32_t bx = static_cast<uint32_t>(x0) >> level; bx <= LastTexel(x1) >> level; ++bx) {
      const double rx0 = std::max(x0, bx * side), rx1 = std::min(x1, (bx + 1) * side);
      uint32_t lo, hi;
      if (index_->RunsAround(bx << level, by << level, level, lo, hi)) {
        if (lo == hi) {  // one colour: colour x overlap area
          AddRunColour(lo, (rx1 - rx0) * (ry1 - ry0), sum);
          continue;
        }
      } else if (level == index_->cell_bits()) {  // a cell with a detail record: its subcells
        IntegrateOverBlocks(level - 2, rx0, ry0, rx1, ry1, sum);
        continue;
      }
      IntegrateByDescent(rx0, ry0, rx1, ry1, sum);
    }
  }
}

void AreaIntegrator::IntegrateByDescent(double x0, double y0, double x1, double y1,
                                        std::array<double, 4>& sum) const {
  const Block start = Enclosing(static_cast<uint32_t>(x0), static_cast<uint32_t>(y0),
                                std::min(LastTexel(x1), texture_.width() - 1),
                                std::min(LastTexel(y1), texture_.height() - 1));
  IntegrateBlock(start, x0, y0, x1, y1, sum);
}

void AreaIntegrator::AddRunColour(size_t run, double area, std::array<double, 4>& sum) const {
  const uint32_t colour = texture_.palette()[texture_.indices()[run]];
  for (int c = 0; c < 4; ++c) sum[c] += area * Channel(colour, c);
}

AreaSum AreaIntegrator::Integrate(double x0, double y0, double x1, double y1) const {
  AreaSum result;
  Piece px[3], py[3];
  const int nx = SplitPeriodic(x0, x1, texture_.width(), px);
  const int ny = SplitPeriodic(y0, y1, texture_.height(), py);
  for (int i = 0; i < nx; ++i) {
    for (int j = 0; j < ny; ++j) {
      const double times = px[i].times * py[j].times;
      const bool whole = px[i].lo == 0 && px[i].hi == texture_.width() && py[j].lo == 0 &&
                         py[j].hi == texture_.height();
      std::array<double, 4> s;
      if (whole) {
        for (int c = 0; c < 4; ++c) s[c] = static_cast<double>(total_[c]);
      } else if (s = {}; !IntegrateOverCells(px[i].lo, py[j].lo, px[i].hi, py[j].hi, s)) {
        IntegrateByDescent(px[i].lo, py[j].lo, px[i].hi, py[j].hi, s);
      }
      for (int c = 0; c < 4; ++c) result.channels[c] += times * s[c];
      result.area += times * (px[i].hi - px[i].lo) * (py[j].hi - py[j].lo);
    }
  }
  return result;
}

}  // namespace aperture::packed
