// The aniso sampler's options: parsed with errors that name the field, validated, and each
// switch or constant changes what a footprint of its regime reads (the defaults are what the
// other aniso tests check).
#include "texture/aniso/aniso_options.h"

#include <gtest/gtest.h>

#include <cmath>

#include "testing/random_image.h"
#include "texture/aniso_selection.h"
#include "texture/prefiltered_table_builder.h"

namespace aperture {
namespace {

TEST(AnisoOptions, ParseSetsFieldsAndNamesWhatIsWrong) {
  auto o = AnisoOptions::Parse("box_probes=false, taps_fade=4,axis_blend_zone=0");
  ASSERT_TRUE(o.ok()) << o.status();
  EXPECT_FALSE(o->box_probes);
  EXPECT_EQ(o->taps_fade, 4.0f);
  EXPECT_EQ(o->axis_blend_zone, 0.0f);
  EXPECT_TRUE(o->base_probes);
  EXPECT_EQ(o->ChangedFields(), "axis_blend_zone=0,taps_fade=4,box_probes=false");
  EXPECT_EQ(AnisoOptions::Parse("")->ChangedFields(), "");

  auto message = [](absl::string_view text) {
    return std::string(AnisoOptions::Parse(text).status().message());
  };
  EXPECT_NE(message("box_probez=false").find("unknown aniso option 'box_probez'"),
            std::string::npos);
  EXPECT_NE(message("taps_fade=fast").find("taps_fade: 'fast' is not a number"), std::string::npos);
  EXPECT_NE(message("box_probes=maybe").find("box_probes: 'maybe' is not true or false"),
            std::string::npos);
  EXPECT_NE(message("probe_half_extent").find("expected NAME=VALUE"), std::string::npos);
  EXPECT_NE(message("probe_half_extent=8").find("probe_half_extent = 8 is outside [0.5, 4]"),
            std::string::npos);
  EXPECT_NE(message("copy_extent_scale=nan").find("copy_extent_scale"), std::string::npos);
}

class AnisoOptionsSelection : public testing::Test {
 protected:
  void SetUp() override {
    auto block = BuildPrefilteredTable(RandomImage(64, 64, 31));
    ASSERT_TRUE(block.ok());
    block_ = *std::move(block);
    auto table = block_.View();
    ASSERT_TRUE(table.ok());
    table_ = *table;
  }
  // Lane 0 of eight equal footprints with half-steps (x0, x1) and (y0, y1) texels (a = 2).
  SelectionLanes Select(const AnisoOptions& o, float x0, float x1, float y0, float y1) {
    const float s = 2.0f / 64;
    float d[4][8];
    for (int lane = 0; lane < 8; ++lane)
      d[0][lane] = x0 * s, d[1][lane] = x1 * s, d[2][lane] = y0 * s, d[3][lane] = y1 * s;
    SelectionLanes out;
    CopySelector(table_, o).Select(d[0], d[1], d[2], d[3], 8, out);
    return out;
  }
  TableBlock block_;
  PrefilteredTable table_;
};

TEST_F(AnisoOptionsSelection, EachSwitchTurnsItsRegimeOff) {
  const AnisoOptions defaults;
  AnisoOptions off = defaults;
  // A short thin footprint along U: H = 3, L = 0.5 (base and box probes).
  EXPECT_GT(Select(defaults, 3, 0, 0, 0.5f).probes[0][0], 0);
  EXPECT_GT(Select(defaults, 3, 0, 0, 0.5f).box_probes[0][0], 0);
  off.base_probes = false;
  EXPECT_EQ(Select(off, 3, 0, 0, 0.5f).probes[0][0], 0);
  EXPECT_GT(Select(off, 3, 0, 0, 0.5f).box_probes[0][0], 0);
  off = defaults, off.box_probes = false;
  EXPECT_GT(Select(off, 3, 0, 0, 0.5f).probes[0][0], 0);
  EXPECT_EQ(Select(off, 3, 0, 0, 0.5f).box_probes[0][0], 0);
  // A magnified footprint (half-axes 0.5 and 0.3 texel): the taps take it whole.
  EXPECT_EQ(Select(defaults, 0.5f, 0, 0, 0.3f).taps_share[0], 1.0f);
  off = defaults, off.magnified_taps = false;
  const SelectionLanes untapped = Select(off, 0.5f, 0, 0, 0.3f);
  EXPECT_EQ(untapped.taps_share[0], 0.0f);
  EXPECT_EQ(untapped.reading_weight[0][0], 1.0f);
  // Turned 30 degrees and magnified: read in its principal axes unless that is off.
  const float c = 0.8660254f, s = 0.5f;
  off = defaults, off.magnified_taps = false;
  const float turned = Select(off, 0.9f * c, 0.9f * s, -0.3f * s, 0.3f * c).probe_scale[0][0];
  off.principal_axes = false;
  EXPECT_LT(turned, 1.0f);
  EXPECT_EQ(Select(off, 0.9f * c, 0.9f * s, -0.3f * s, 0.3f * c).probe_scale[0][0], 1.0f);
  // Near a diagonal both readings are read, with no zone only one.
  EXPECT_GT(Select(defaults, 4, 3.9f, -0.5f, 0.5f).reading_weight[1][0], 0.0f);
  off = defaults, off.axis_blend_zone = 0;
  EXPECT_EQ(Select(off, 4, 3.9f, -0.5f, 0.5f).reading_weight[1][0], 0.0f);
  // A footprint of half-extent 100 texels (past the 64-texel period) along tg = -0.8: its cells'
  // paper tilts are -0.75 and -0.25, and the end tilt tg = -1 is read only when switched on.
  auto reads_an_end = [&](const AnisoOptions& o) {
    const SelectionLanes l = Select(o, 100, -80, 2.4f, 3);
    for (int r = 0; r < 2; ++r)
      for (int slot = 0; slot < SelectionLanes::kSlots; ++slot)
        if (l.reading_weight[r][0] > 0 && l.weight[r][slot][0] > 0 &&
            std::abs(table_.copy(l.copy[r][slot][0]).tg) == 1.0f)
          return true;
    return false;
  };
  EXPECT_FALSE(reads_an_end(defaults));
  off = defaults, off.end_tilts_beyond_period = true;
  EXPECT_TRUE(reads_an_end(off));
}

TEST_F(AnisoOptionsSelection, TheCopyExtentScaleChoosesTheCells) {
  // H = 6, L = 3 texels: at c^2 = 0.8 x^2 + 0.2 the copies are shorter than at c = x, so the
  // blend's weights differ.
  AnisoOptions paper;
  paper.copy_extent_scale = 1.0f;
  const SelectionLanes a = Select({}, 6, 0, 0, 3), b = Select(paper, 6, 0, 0, 3);
  bool differs = false;
  for (int slot = 0; slot < SelectionLanes::kSlots; ++slot)
    differs = differs || a.weight[0][slot][0] != b.weight[0][slot][0] ||
              (a.weight[0][slot][0] > 0 && a.copy[0][slot][0] != b.copy[0][slot][0]);
  EXPECT_TRUE(differs);
}

}  // namespace
}  // namespace aperture
