#include "log_text.h"

#include <gtest/gtest.h>

namespace aperture {
namespace {

TEST(LogText, ALineStaysOneLineWhateverTheClientSent) {
  EXPECT_EQ(LogText("airfield"), "airfield");
  const std::string forged = "x' status=OK\n[2026-11-25] [aperture-server] [info] req=9 forged";
  const std::string logged = LogText(forged);
  EXPECT_EQ(logged.find('\n'), std::string::npos);
  EXPECT_EQ(logged.rfind("x\\' status", 0), 0u) << logged;  // the quote is escaped
  EXPECT_NE(logged.find("\\n[2026"), std::string::npos);
  EXPECT_EQ(LogText(std::string("a\0b\x7f\xff", 5)), "a\\x00b\\x7f\\xff");
}

TEST(LogText, LongTextIsCutWithACount) {
  const std::string logged = LogText(std::string(1000, 'a'), 10);
  EXPECT_EQ(logged, "aaaaaaaaaa...(990 more bytes)");
  // An escape is never cut in half.
  EXPECT_EQ(LogText("abcdefghi\n", 10), "abcdefghi...(1 more bytes)");
}

}  // namespace
}  // namespace aperture
