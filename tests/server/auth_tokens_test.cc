#include "auth_tokens.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>

namespace aperture {
namespace {

class AuthTokensTest : public ::testing::Test {
 protected:
  void Write(const std::string& content) { std::ofstream(path_) << content; }
  void TearDown() override { std::remove(path_.c_str()); }
  const std::string path_ = ::testing::TempDir() + "tokens_" + std::to_string(getpid());
};

TEST_F(AuthTokensTest, OnlyBearerTokensFromTheFileAreAccepted) {
  Write("# comment\n  alpha  \n\nbeta\n");
  auto tokens = AuthTokens::Load(path_);
  ASSERT_TRUE(tokens.ok()) << tokens.status();
  EXPECT_TRUE((*tokens)->CheckHeader("Bearer alpha").ok());
  EXPECT_TRUE((*tokens)->CheckHeader("Bearer beta").ok());
  EXPECT_TRUE(absl::IsUnauthenticated((*tokens)->CheckHeader("Bearer gamma")));
  EXPECT_TRUE(absl::IsUnauthenticated((*tokens)->CheckHeader("alpha")));
  EXPECT_TRUE(absl::IsUnauthenticated((*tokens)->CheckHeader("")));
  EXPECT_TRUE(absl::IsUnauthenticated((*tokens)->CheckHeader("Bearer # comment")));
  // The refusal never repeats what was sent.
  EXPECT_EQ((*tokens)->CheckHeader("Bearer gamma").message().find("gamma"), std::string::npos);
}

TEST_F(AuthTokensTest, ReloadReplacesTheTokensUnlessTheFileIsBad) {
  Write("alpha\n");
  auto tokens = AuthTokens::Load(path_);
  ASSERT_TRUE(tokens.ok());
  Write("beta\n");
  ASSERT_TRUE((*tokens)->Reload().ok());
  EXPECT_FALSE((*tokens)->CheckHeader("Bearer alpha").ok());
  EXPECT_TRUE((*tokens)->CheckHeader("Bearer beta").ok());
  Write("# nothing\n");
  EXPECT_FALSE((*tokens)->Reload().ok());
  EXPECT_TRUE((*tokens)->CheckHeader("Bearer beta").ok());  // kept
  EXPECT_FALSE(AuthTokens::Load(path_ + ".missing").ok());
}

}  // namespace
}  // namespace aperture
