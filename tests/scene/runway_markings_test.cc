// Runway markings to ICAO Annex 14 (docs/SCENE.md, "Runway markings"): the rectangles against the
// Annex's figures, the packed texture against a rasterised reference of the same rectangles, and
// bad runway data refused naming the field.
#include "scene/runway_markings.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "scene/airport_runways.h"
#include "texture/packed/apv_file.h"
#include "texture/packed/area_integral.h"
#include "texture/packed/packed_sampler.h"

namespace aperture {
namespace {

RunwayDescription Runway(const char* designator, double width_m, double length_m,
                         RunwayCategory category = RunwayCategory::kPrecisionCatI) {
  RunwayDescription r;
  r.designator = designator;
  r.threshold = {10, 0, -20};
  r.heading_deg = 27;
  r.length_m = length_m;
  r.width_m = width_m;
  r.category = category;
  return r;
}

std::vector<MarkingRect> Of(const std::vector<MarkingRect>& rects, MarkingKind kind,
                            const std::string& end) {
  std::vector<MarkingRect> out;
  for (const MarkingRect& m : rects)
    if (m.kind == kind && m.end == end) out.push_back(m);
  std::sort(out.begin(), out.end(), [](const MarkingRect& a, const MarkingRect& b) {
    return a.y0 != b.y0 ? a.y0 < b.y0 : a.x0 < b.x0;
  });
  return out;
}

TEST(RunwayMarkings, ThresholdStripesNumberByWidth) {
  // Annex 14 5.2.4.6: 8 stripes on a 30 m runway, 12 on 45 m, 16 on 60 m; 30 m long from 6 m
  // past the threshold (5.2.4.4, 5.2.4.5), about 1.8 m wide and apart, reaching to within 3 m of
  // the edges or 27 m of the centre line.
  for (const auto& [width, count] : {std::pair{30.0, 8}, {45.0, 12}, {60.0, 16}}) {
    auto rects = RunwayMarkingRects(Runway("09", width, 2500));
    ASSERT_TRUE(rects.ok()) << rects.status();
    for (const char* end : {"09", "27"}) {
      const auto stripes = Of(*rects, MarkingKind::kThreshold, end);
      ASSERT_EQ(stripes.size(), static_cast<size_t>(count)) << width << " m, end " << end;
      const bool near = std::string(end) == "09";
      for (const MarkingRect& s : stripes) {
        const double from_threshold = near ? s.y0 : 2500 - s.y1;
        EXPECT_NEAR(from_threshold, 6, 0.75);
        EXPECT_NEAR(s.y1 - s.y0, 30, 0.75);
        EXPECT_GE(s.x1 - s.x0, 1.4);
        EXPECT_LE(s.x1 - s.x0, 1.8 + 1e-9);
        EXPECT_GE(s.x0, 3 - 1e-9);
        EXPECT_LE(s.x1, width - 3 + 1e-9);
        EXPECT_GE(s.x0, width / 2 - 27 - 1e-9);
        EXPECT_LE(s.x1, width / 2 + 27 + 1e-9);
      }
      // Symmetric about the centre line, with none on it.
      int left = 0, right = 0;
      for (const MarkingRect& s : stripes) (s.x1 <= width / 2 ? left : right) += 1;
      EXPECT_EQ(left, count / 2);
      EXPECT_EQ(right, count / 2);
    }
  }
}

TEST(RunwayMarkings, ThePolderbaansLayoutFollowsAnnex14) {
  const RunwayDescription r = Polderbaan36L();  // 3,800 m x 60 m, category III
  auto rects = RunwayMarkingRects(r);
  ASSERT_TRUE(rects.ok()) << rects.status();

  // Aiming point (Table 5-1, LDA 2,400 m or more): two stripes from 400 m, 45 m long, 6-10 m
  // wide, 18-22.5 m apart between their inner sides.
  const auto aiming = Of(*rects, MarkingKind::kAimingPoint, "36L");
  ASSERT_EQ(aiming.size(), 2u);
  for (const MarkingRect& a : aiming) {
    EXPECT_DOUBLE_EQ(a.y0, 400);
    EXPECT_DOUBLE_EQ(a.y1 - a.y0, 45);
    EXPECT_GE(a.x1 - a.x0, 6);
    EXPECT_LE(a.x1 - a.x0, 10);
  }
  EXPECT_GE(aiming[1].x0 - aiming[0].x1, 18 - 1e-9);
  EXPECT_LE(aiming[1].x0 - aiming[0].x1, 22.5 + 1e-9);

  // Touchdown zone (5.2.6, Figure 5-6 (B)): pairs every 150 m, 22.5 m long, stripes 1.8 m wide and
  // 1.5 m apart, 3, 3, 2, 2, 1, 1 of them; the 450 m pair within 50 m of the aiming point left
  // out.
  std::map<double, int> stripes_at;
  for (const MarkingRect& t : Of(*rects, MarkingKind::kTouchdownZone, "36L")) {
    EXPECT_DOUBLE_EQ(t.y1 - t.y0, 22.5);
    EXPECT_NEAR(t.x1 - t.x0, 1.8, 1e-9);
    ++stripes_at[t.y0];
  }
  const std::map<double, int> expected = {{150, 6}, {300, 6}, {600, 4}, {750, 2}, {900, 2}};
  EXPECT_EQ(stripes_at, expected);

  // Centre line (5.2.3): 0.9 m wide on a category III runway, 30 m stripes and 20 m gaps, from
  // beyond one designation marking to the other.
  const auto centre = Of(*rects, MarkingKind::kCentreLine, "36L");
  ASSERT_GT(centre.size(), 60u);
  for (size_t i = 0; i < centre.size(); ++i) {
    EXPECT_NEAR(centre[i].x1 - centre[i].x0, 0.9, 1e-9);
    EXPECT_NEAR((centre[i].x0 + centre[i].x1) / 2, 30, 1e-9);
    EXPECT_NEAR(centre[i].y1 - centre[i].y0, 30, 0.75);
    if (i > 0) {
      EXPECT_NEAR(centre[i].y0 - centre[i - 1].y1, 20, 0.75);
    }
  }
  EXPECT_GT(centre.front().y0, 72);  // past 36L's designation, which ends 72 m in
  EXPECT_LT(centre.back().y1, 3800 - 72);

  // Side stripes (5.2.7): 0.9 m along both edges, the whole length.
  const auto sides = Of(*rects, MarkingKind::kSideStripe, "36L");
  ASSERT_EQ(sides.size(), 2u);
  EXPECT_DOUBLE_EQ(sides[0].x0, 0);
  EXPECT_NEAR(sides[0].x1, 0.9, 1e-9);
  EXPECT_NEAR(sides[1].x0, 59.1, 1e-9);
  EXPECT_DOUBLE_EQ(sides[1].x1, 60);

  // Designation (5.2.2, Figure 5-3): "L" nearer the threshold, then "36", 9 m tall, beyond the
  // threshold stripes; at the far end "18R" likewise, turned round.
  for (const char* end : {"36L", "18R"}) {
    const auto glyphs = Of(*rects, MarkingKind::kDesignation, end);
    ASSERT_FALSE(glyphs.empty()) << end;
    double lo = 1e9, hi = -1e9;
    for (const MarkingRect& g : glyphs) {
      const double y0 = std::string(end) == "36L" ? g.y0 : 3800 - g.y1;
      const double y1 = std::string(end) == "36L" ? g.y1 : 3800 - g.y0;
      lo = std::min(lo, y0), hi = std::max(hi, y1);
    }
    EXPECT_NEAR(lo, 48, 0.75) << end;  // 12 m past the stripes' end at 36 m
    EXPECT_NEAR(hi, 48 + 9 + 6 + 9, 0.75) << end;
  }
  EXPECT_EQ(Of(*rects, MarkingKind::kAimingPoint, "18R").size(), 2u);
}

TEST(RunwayMarkings, PackIntoAFewRuns) {
  // Two colours in long rectangles: the 6 million texels of 36L pack into 31,348 runs, a 64 KB
  // .apv (the side stripes and the centre line cross most of the Hilbert curve's blocks).
  auto texture = RunwayMarkingsTexture(Polderbaan36L());
  ASSERT_TRUE(texture.ok()) << texture.status();
  EXPECT_EQ(texture->view().width(), 400u);
  EXPECT_EQ(texture->view().height(), 15200u);
  const size_t apv = packed::EncodeApv(texture->view()).size();
  EXPECT_LT(texture->view().run_count(), 40000u);
  EXPECT_LT(apv, 80u * 1024);
}

TEST(RunwayMarkings, ReciprocalDesignators) {
  EXPECT_EQ(ReciprocalDesignator("36L"), "18R");
  EXPECT_EQ(ReciprocalDesignator("18R"), "36L");
  EXPECT_EQ(ReciprocalDesignator("09C"), "27C");
  EXPECT_EQ(ReciprocalDesignator("01"), "19");
  EXPECT_EQ(ReciprocalDesignator("19"), "01");
}

// The texture against a rasterised reference of its own rectangles: dense points (every texel's
// centre near each end, every eighth row between) are paint exactly when a rectangle holds them;
// the exact area integral over every rectangle is all paint, and over the gaps between threshold
// stripes all asphalt.
void ExpectTextureMatchesRectangles(const RunwayDescription& r) {
  SCOPED_TRACE(r.designator);
  auto rects = RunwayMarkingRects(r);
  ASSERT_TRUE(rects.ok()) << rects.status();
  auto texture = RunwayMarkingsTexture(r);
  ASSERT_TRUE(texture.ok()) << texture.status();
  const packed::PackedTextureView& view = texture->view();
  const double texel_x = r.width_m / view.width();
  ASSERT_NEAR(texel_x, kMarkingTexelAcrossM, 0.01);
  const double length_texels = view.height() * kMarkingTexelAlongM;
  ASSERT_GE(length_texels, r.length_m);
  ASSERT_LT(length_texels - r.length_m, kMarkingTexelAlongM);
  const packed::PackedTextureSampler sampler(view, packed::PackedSampling::kNearest);

  int samples = 0, paint = 0, wrong = 0;
  // One sample at every texel's centre over the first and last 1,000 m (every marking but the
  // middle of the centre line), every eighth row in between.
  const int rows = static_cast<int>(view.height());
  for (int j = 0; j < rows; ++j) {
    const double y = (j + 0.5) * kMarkingTexelAlongM;
    if (y > 1000 && y < r.length_m - 1000 && j % 8 != 0) continue;
    std::vector<const MarkingRect*> across;  // the rectangles this row crosses
    for (const MarkingRect& m : *rects)
      if (y >= m.y0 && y < m.y1) across.push_back(&m);
    for (uint32_t i = 0; i < view.width(); ++i) {
      const double x = (i + 0.5) * texel_x;
      bool expected = false;
      for (const MarkingRect* m : across) expected = expected || (x >= m->x0 && x < m->x1);
      const Rgba c = sampler.Nearest(x / r.width_m, y / length_texels);
      const bool got = std::abs(c.r - kPaintWhite / 255.0f) < 1e-6f;
      if (!got) {
        EXPECT_NEAR(c.r, kAsphaltGrey / 255.0f, 1e-6f);
      }
      ++samples, paint += expected, wrong += expected != got;
      if (expected != got && wrong <= 5)
        ADD_FAILURE() << "at x " << x << " m, y " << y << " m: expected "
                      << (expected ? "paint" : "asphalt");
    }
  }
  EXPECT_EQ(wrong, 0) << "of " << samples;
  EXPECT_GT(paint, samples / 50);

  // Exact area integrals (texel units: x / texel_x, y / 0.75).
  const packed::AreaIntegrator area(view);
  for (const MarkingRect& m : *rects) {
    const packed::AreaSum s = area.Integrate(m.x0 / texel_x, m.y0 / kMarkingTexelAlongM,
                                             m.x1 / texel_x, m.y1 / kMarkingTexelAlongM);
    ASSERT_GT(s.area, 0);
    EXPECT_NEAR(s.channels[0] / s.area, kPaintWhite, 1e-6)
        << "rectangle kind " << static_cast<int>(m.kind) << " at " << m.x0 << ", " << m.y0;
  }
  auto stripes = Of(*rects, MarkingKind::kThreshold, r.designator);
  for (size_t i = 1; i < stripes.size(); ++i) {
    const MarkingRect &a = stripes[i - 1], &b = stripes[i];
    ASSERT_GT(b.x0, a.x1);
    const packed::AreaSum gap = area.Integrate(a.x1 / texel_x, a.y0 / kMarkingTexelAlongM,
                                               b.x0 / texel_x, a.y1 / kMarkingTexelAlongM);
    EXPECT_NEAR(gap.channels[0] / gap.area, kAsphaltGrey, 1e-6) << "between stripes " << i;
  }
}

TEST(RunwayMarkings, TextureMatchesARasterisedReferenceOfItsRectangles) {
  ExpectTextureMatchesRectangles(Polderbaan36L());
  ExpectTextureMatchesRectangles(Zwanenburgbaan36C());
  ExpectTextureMatchesRectangles(Runway("27", 30, 1700.3, RunwayCategory::kNonPrecision));
}

TEST(RunwayMarkings, BadRunwayDataIsRefusedNamingTheField) {
  struct Case {
    RunwayDescription runway;
    const char* field;
  };
  RunwayDescription zero_width = Runway("36L", 0, 3000);
  RunwayDescription unknown = Runway("37X", 45, 3000);
  RunwayDescription narrow = Runway("04", 10, 3000);
  RunwayDescription short_runway = Runway("22R", 45, 150);
  short_runway.papi_distance_m = 50;  // within the length: the markings' own check speaks
  RunwayDescription nan_threshold = Runway("22", 45, 3000);
  nan_threshold.threshold.x = std::nan("");
  for (const Case& c :
       {Case{zero_width, "width_m"}, Case{unknown, "designator"}, Case{narrow, "width_m"},
        Case{short_runway, "length_m"}, Case{nan_threshold, "threshold"}}) {
    auto rects = RunwayMarkingRects(c.runway);
    ASSERT_FALSE(rects.ok()) << c.field;
    EXPECT_EQ(rects.status().code(), absl::StatusCode::kInvalidArgument);
    EXPECT_NE(rects.status().message().find(c.field), std::string::npos) << rects.status();
    EXPECT_NE(rects.status().message().find(c.runway.designator), std::string::npos);
    v1::Scene scene;
    EXPECT_FALSE(AddRunwayMarkings(c.runway, &scene).ok());
    EXPECT_EQ(scene.textures_size() + scene.materials_size() + scene.meshes_size(), 0);
  }
}

TEST(RunwayMarkings, DrapedOnTheRunwayWithTheTextureMapped) {
  const RunwayDescription r = Zwanenburgbaan36C();
  v1::Scene scene;
  ASSERT_TRUE(AddRunwayMarkings(r, &scene).ok());
  ASSERT_EQ(scene.meshes_size(), 1);
  EXPECT_EQ(scene.meshes(0).id(), "runway-36C");
  EXPECT_EQ(scene.textures(0).id(), "runway-markings-36C");
  const v1::Polygon& p = scene.meshes(0).polygons(0);
  ASSERT_EQ(p.vertices_size(), 4);
  ASSERT_EQ(p.uvs_size(), 4);
  // The threshold's centre is the midpoint of the first two corners; the far end's is the length
  // away along the heading.
  const Vec3 a{p.vertices(0).x(), p.vertices(0).y(), p.vertices(0).z()};
  const Vec3 b{p.vertices(1).x(), p.vertices(1).y(), p.vertices(1).z()};
  const Vec3 c{p.vertices(2).x(), p.vertices(2).y(), p.vertices(2).z()};
  const Vec3 mid = (a + b) * 0.5;
  EXPECT_NEAR(mid.x, r.threshold.x, 1e-9);
  EXPECT_NEAR(mid.z, r.threshold.z, 1e-9);
  EXPECT_NEAR(mid.y, r.threshold.y + 0.01, 1e-9);
  EXPECT_NEAR(Length(b - a), r.width_m, 1e-9);
  EXPECT_NEAR(Length(c - b), r.length_m, 1e-9);
  // A second time is refused: the ids are taken.
  EXPECT_FALSE(AddRunwayMarkings(r, &scene).ok());
}

}  // namespace
}  // namespace aperture
