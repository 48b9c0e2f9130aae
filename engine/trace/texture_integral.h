// What seed 003's eq. 3 needs from a texture: the integral of its continuous form over an
// axis-aligned rectangle of the texture plane (texel units, fractional edges). Raster textures
// answer from their summed-area tables; packed vector textures (seed 001) from their own exact
// area integral over the runs, without unpacking.
#pragma once

#include <array>
#include <vector>

#include "texture/packed/area_integral.h"
#include "texture/summed_area_table.h"

namespace aperture {

class TextureIntegral {
 public:
  virtual ~TextureIntegral() = default;
  virtual int width() const = 0;
  virtual int height() const = 0;
  virtual int channels() const = 0;  // 3: alpha is 1
  // The integral of colour (channels in [0, 1]) over [x0, x1] x [y0, y1], texel units, within one
  // period (0 <= x0 <= x1 <= width, likewise y).
  virtual std::array<double, 4> Integrate(double x0, double y0, double x1, double y1) const = 0;
  // The same over any rectangle of the periodic plane.
  virtual std::array<double, 4> IntegratePeriodic(double x0, double y0, double x1,
                                                  double y1) const = 0;
  // The summed-area table of mip level `level` behind it (0: the texture itself), for exact
  // integrals over polygons; null when it has none.
  virtual const SummedAreaTable* table(int /*level*/) const { return nullptr; }
};

// A raster texture: the bilinear texture's integral from its summed-area table, and the tables
// of its coarser mip levels when given (the base first).
class TableIntegral final : public TextureIntegral {
 public:
  explicit TableIntegral(const SummedAreaTable& table) : table_(table), levels_{&table} {}
  explicit TableIntegral(std::vector<const SummedAreaTable*> levels)
      : table_(*levels.front()), levels_(std::move(levels)) {}
  int width() const override { return table_.width(); }
  int height() const override { return table_.height(); }
  int channels() const override { return table_.channels(); }
  std::array<double, 4> Integrate(double x0, double y0, double x1, double y1) const override {
    return table_.Integrate(x0, y0, x1, y1);
  }
  std::array<double, 4> IntegratePeriodic(double x0, double y0, double x1,
                                          double y1) const override {
    return table_.IntegratePeriodic(x0, y0, x1, y1);
  }
  const SummedAreaTable* table(int level) const override {
    return level >= 0 && level < static_cast<int>(levels_.size()) ? levels_[level] : nullptr;
  }

 private:
  const SummedAreaTable& table_;
  std::vector<const SummedAreaTable*> levels_;
};

// A packed vector texture: texels constant over their squares (a palette image), integrated over
// the curve's aligned blocks and runs (texture/packed/area_integral), 8-bit values / 255.
class PackedIntegral final : public TextureIntegral {
 public:
  PackedIntegral(const packed::AreaIntegrator& area, int width, int height)
      : area_(area), width_(width), height_(height) {}
  int width() const override { return width_; }
  int height() const override { return height_; }
  int channels() const override { return 4; }
  std::array<double, 4> Integrate(double x0, double y0, double x1, double y1) const override {
    return IntegratePeriodic(x0, y0, x1, y1);
  }
  std::array<double, 4> IntegratePeriodic(double x0, double y0, double x1,
                                          double y1) const override {
    const packed::AreaSum s = area_.Integrate(x0, y0, x1, y1);
    constexpr double k = 1.0 / 255.0;
    return {s.channels[0] * k, s.channels[1] * k, s.channels[2] * k, s.channels[3] * k};
  }

 private:
  const packed::AreaIntegrator& area_;
  int width_, height_;
};

}  // namespace aperture
