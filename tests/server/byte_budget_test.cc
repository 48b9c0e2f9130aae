#include "byte_budget.h"

#include <gtest/gtest.h>

namespace aperture {
namespace {

TEST(ByteBudget, ReservationsHoldBytesUntilTheyGo) {
  ByteBudget budget("uploads in flight (--max-upload-inflight-mb)", 100);
  {
    auto a = budget.Reserve(60);
    ASSERT_TRUE(a.ok());
    EXPECT_EQ(budget.used(), 60u);
    auto b = budget.Reserve(50);
    ASSERT_FALSE(b.ok());
    EXPECT_TRUE(absl::IsResourceExhausted(b.status()));
    EXPECT_NE(b.status().message().find("--max-upload-inflight-mb"), std::string::npos);
    ByteReservation moved = *std::move(a);
    EXPECT_EQ(budget.used(), 60u);  // moving does not return the bytes
    moved.Release();
    EXPECT_EQ(budget.used(), 0u);
    auto c = budget.Reserve(100);
    EXPECT_TRUE(c.ok());
  }
  EXPECT_EQ(budget.used(), 0u);
}

TEST(ByteBudget, ARequestAloneAboveTheBudgetSaysSo) {
  ByteBudget budget("scenes (--max-scene-mb)", 1 << 20);
  auto big = budget.Reserve(3 << 20);
  ASSERT_FALSE(big.ok());
  EXPECT_NE(big.status().message().find("this request alone needs 3 MiB"), std::string::npos)
      << big.status();
}

}  // namespace
}  // namespace aperture
