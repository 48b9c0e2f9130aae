// The quadrant split: the quadrants tile the window exactly, in reading order, a side longer than
// the limit is halved (the first half the shorter of an odd side), a side within it stays whole.
#include "raster/window_quadrants.h"

#include <gtest/gtest.h>

#include <vector>

namespace aperture {
namespace {

// How often each pixel of `window` lies in one of `quads` (1 everywhere: a tiling).
std::vector<int> Coverage(const WindowQuadrants& quads, const PixelRect& window) {
  std::vector<int> hits(static_cast<size_t>(window.pixels()), 0);
  for (const PixelRect& q : quads)
    for (int y = q.y0; y < q.y1; ++y)
      for (int x = q.x0; x < q.x1; ++x) {
        if (x < window.x0 || x >= window.x1 || y < window.y0 || y >= window.y1) {
          ADD_FAILURE() << "pixel (" << x << ", " << y << ") outside the window";
          continue;
        }
        ++hits[static_cast<size_t>((y - window.y0) * window.width() + (x - window.x0))];
      }
  return hits;
}

void ExpectRect(const PixelRect& r, int x0, int y0, int x1, int y1) {
  EXPECT_EQ(r.x0, x0);
  EXPECT_EQ(r.y0, y0);
  EXPECT_EQ(r.x1, x1);
  EXPECT_EQ(r.y1, y1);
}

TEST(WindowQuadrants, BothSidesLongerAreHalvedInReadingOrder) {
  const WindowQuadrants q = SplitWindow({10, 20, 27, 40}, 8);  // 17 x 20
  ASSERT_EQ(q.count, 4);
  ExpectRect(q.rects[0], 10, 20, 18, 30);  // 17 / 2 = 8 columns, then 9
  ExpectRect(q.rects[1], 18, 20, 27, 30);
  ExpectRect(q.rects[2], 10, 30, 18, 40);
  ExpectRect(q.rects[3], 18, 30, 27, 40);
}

TEST(WindowQuadrants, ASideWithinTheLimitStaysWhole) {
  const WindowQuadrants wide = SplitWindow({0, 0, 64, 16}, 16);  // only x is longer than 16
  ASSERT_EQ(wide.count, 2);
  ExpectRect(wide.rects[0], 0, 0, 32, 16);
  ExpectRect(wide.rects[1], 32, 0, 64, 16);
  const WindowQuadrants tall = SplitWindow({0, 0, 3, 9}, 8);  // only y
  ASSERT_EQ(tall.count, 2);
  ExpectRect(tall.rects[0], 0, 0, 3, 4);
  ExpectRect(tall.rects[1], 0, 4, 3, 9);
}

TEST(WindowQuadrants, AWindowWithinTheLimitIsALeaf) {
  EXPECT_TRUE(SplitWindow({0, 0, 16, 16}, 16).empty());
  EXPECT_TRUE(SplitWindow({5, 7, 6, 8}, 8).empty());
  EXPECT_FALSE(SplitWindow({0, 0, 17, 1}, 16).empty());
}

TEST(WindowQuadrants, TheQuadrantsTileTheWindowForEverySize) {
  for (int max_side : {1, 8, 16, 64})
    for (int w = 1; w <= 70; w += 3)
      for (int h = 1; h <= 70; h += 5) {
        const PixelRect window{3, -2, 3 + w, -2 + h};
        const WindowQuadrants q = SplitWindow(window, max_side);
        if (w <= max_side && h <= max_side) {
          EXPECT_TRUE(q.empty());
          continue;
        }
        EXPECT_EQ(q.count, (w > max_side ? 2 : 1) * (h > max_side ? 2 : 1));
        for (const PixelRect& r : q) EXPECT_TRUE(r.width() > 0 && r.height() > 0);
        for (int hits : Coverage(q, window)) ASSERT_EQ(hits, 1) << w << "x" << h;
      }
}

}  // namespace
}  // namespace aperture
