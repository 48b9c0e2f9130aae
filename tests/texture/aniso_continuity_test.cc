// The seed 000 sampler is continuous in the footprint. A tiny change of the
// footprint (turned, stretched or thickened a little) changes the sample by a tiny amount, so
// that no boundary between copies, tilts or probe counts shows in a frame as a seam.
//
// How it is checked: footprints are swept along paths that cross every such boundary (turns
// through 180 degrees, lengths from a tenth of a texel to many periods, thicknesses from a
// tenth of a texel to the length). The largest steps of each sweep are then bisected: a
// continuous sampler's step shrinks with the interval (about halves per bisection); a jump
// keeps its size however small the interval.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "testing/random_image.h"
#include "texture/aniso_sampler.h"
#include "texture/prefiltered_table_builder.h"

namespace aperture {
namespace {

constexpr int kN = 64;

// A footprint at (u, v) whose pixel steps are `len` texels along angle `turn` and `thick`
// texels across it (a = 1).
TextureFootprint Turned(double len, double thick, double turn, double u, double v) {
  const double c = std::cos(turn), s = std::sin(turn), k = 1.0 / kN;
  return {
      u, v, float(len * c * k), float(len * s * k), float(-thick * s * k), float(thick * c * k)};
}

double Difference(const Rgba& a, const Rgba& b) {
  return std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
}

struct Sweep {
  const char* name;
  std::function<TextureFootprint(double)> at;  // t in [0, 1]
};

struct Jump {
  double t0, t1, size;
};

// The step of `steps` equal steps of t with the largest change, bisected `levels` times towards
// its larger half: what is left of the change over an interval 2^-levels of a step.
Jump WorstJumpAfterBisection(const AnisoSampler& sampler, const Sweep& sweep, int steps, int levels,
                             double* worst_step) {
  std::vector<std::pair<double, int>> changes;
  Rgba previous = sampler.Sample(sweep.at(0));
  for (int i = 1; i <= steps; ++i) {
    const Rgba next = sampler.Sample(sweep.at(double(i) / steps));
    changes.push_back({Difference(previous, next), i - 1});
    previous = next;
  }
  std::sort(changes.rbegin(), changes.rend());
  *worst_step = changes.front().first;
  Jump worst{0, 0, 0};
  // The 16 largest steps: a seam is among them if there is one.
  for (size_t k = 0; k < std::min<size_t>(16, changes.size()); ++k) {
    double t0 = double(changes[k].second) / steps, t1 = double(changes[k].second + 1) / steps;
    Rgba a = sampler.Sample(sweep.at(t0)), b = sampler.Sample(sweep.at(t1));
    for (int level = 0; level < levels; ++level) {
      const double tm = 0.5 * (t0 + t1);
      const Rgba m = sampler.Sample(sweep.at(tm));
      if (Difference(a, m) >= Difference(m, b)) {
        t1 = tm, b = m;
      } else {
        t0 = tm, a = m;
      }
    }
    const double size = Difference(a, b);
    if (size > worst.size) worst = {t0, t1, size};
  }
  return worst;
}

class AnisoContinuityTest : public testing::Test {
 protected:
  void SetUp() override {
    auto block = BuildPrefilteredTable(RandomImage(kN, kN, 2203));
    ASSERT_TRUE(block.ok()) << block.status();
    block_ = std::move(*block);
    auto table = block_.View();
    ASSERT_TRUE(table.ok()) << table.status();
    sampler_ = std::make_unique<AnisoSampler>(*table);
  }
  TableBlock block_;
  std::unique_ptr<AnisoSampler> sampler_;
};

TEST_F(AnisoContinuityTest, ATinyChangeOfTheFootprintChangesTheSampleByATinyAmount) {
  std::vector<Sweep> sweeps;
  // Turns through 180 degrees: every tilt boundary of each cell, the change of major axis at 45
  // and 135 degrees, both signs of the tangent.
  // Nearly round ones too: their readings along U and V nearly agree, and the zone where both
  // are read is as narrow in angle for them as for the others.
  const double shapes[][2] = {{1.5, 0.4}, {5, 0.6},      {12, 1.5}, {40, 2.5}, {300, 3},
                              {3000, 40}, {200000, 300}, {2, 1.2},  {10, 9.5}, {0.9, 0.85}};
  for (const auto& shape : shapes)
    sweeps.push_back({"turn", [len = shape[0], thick = shape[1]](double t) {
                        return Turned(len, thick, M_PI * t, 0.37, 0.61);
                      }});
  // Lengths from 0.1 texel to 10^5 texels at a fixed turn: magnification, the base probes and
  // their counts, every cell of the table, the frozen region, whole periods.
  for (double thick : {0.3, 0.8, 3.0})
    sweeps.push_back({"length", [thick](double t) {
                        return Turned(std::max(thick, 0.1 * std::pow(1e6, t)), thick, 0.3, 0.21,
                                      0.83);
                      }});
  // Thicknesses from 0.05 texel to the length.
  for (double len : {3.0, 10.0, 100.0, 5000.0})
    sweeps.push_back({"thickness", [len](double t) {
                        return Turned(len, 0.05 * std::pow(len / 0.05, t), 0.6, 0.55, 0.09);
                      }});
  // Both at once, at 45 degrees (the change of major axis).
  sweeps.push_back({"scale at 45 degrees", [](double t) {
                      const double s = 0.1 * std::pow(1e5, t);
                      return Turned(s, 0.3 * s, M_PI / 4, 0.7, 0.45);
                    }});

  double worst_jump = 0;
  for (const Sweep& sweep : sweeps) {
    double worst_step = 0;
    const Jump jump = WorstJumpAfterBisection(*sampler_, sweep, 4000, 20, &worst_step);
    const TextureFootprint f = sweep.at(jump.t0);
    SCOPED_TRACE(testing::Message()
                 << sweep.name << ": largest step " << worst_step << "; after bisection "
                 << jump.size << " at t = " << jump.t0 << " (derivatives " << f.dudx * kN << " "
                 << f.dvdx * kN << " " << f.dudy * kN << " " << f.dvdy * kN << " texels)");
    std::printf("%-22s largest of 4000 steps %.5f, left after 2^-20 of a step %.2e\n", sweep.name,
                worst_step, jump.size);
    // Continuous: what is left of the step over 2^-20 of it is float rounding. A seam keeps its
    // size (on these random texels a jump between copies is 0.01 to 0.1).
    EXPECT_LT(jump.size, 1e-4);
    worst_jump = std::max(worst_jump, jump.size);
  }
  std::printf("worst change left after bisection: %.2e\n", worst_jump);
}

}  // namespace
}  // namespace aperture
