#include "auth_tokens.h"

#include <fstream>
#include <string_view>

#include "absl/strings/ascii.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"
#include "content_hash.h"

namespace aperture {
namespace {

constexpr absl::string_view kBearer = "Bearer ";

}  // namespace

absl::StatusOr<std::set<std::string>> AuthTokens::ReadDigests(const std::string& path) {
  std::ifstream in(path);
  if (!in) return absl::NotFoundError(absl::StrCat("--auth-tokens ", path, ": cannot read"));
  std::set<std::string> digests;
  std::string line;
  while (std::getline(in, line)) {
    const absl::string_view token = absl::StripAsciiWhitespace(line);
    if (token.empty() || token.front() == '#') continue;  // blank lines and comments
    digests.insert(Sha256Hex(std::string_view(token.data(), token.size())));
  }
  if (digests.empty())
    return absl::InvalidArgumentError(
        absl::StrCat("--auth-tokens ", path, ": no token in the file (one per line)"));
  return digests;
}

absl::StatusOr<std::unique_ptr<AuthTokens>> AuthTokens::Load(const std::string& path) {
  std::unique_ptr<AuthTokens> tokens(new AuthTokens(path));
  auto reloaded = tokens->Reload();
  if (!reloaded.ok()) return reloaded.status();
  return tokens;
}

absl::StatusOr<size_t> AuthTokens::Reload() {
  auto digests = ReadDigests(path_);
  if (!digests.ok()) return digests.status();
  const size_t count = digests->size();
  std::lock_guard<std::mutex> lock(mutex_);
  digests_ = std::make_shared<const std::set<std::string>>(*std::move(digests));
  return count;
}

absl::Status AuthTokens::CheckHeader(absl::string_view authorization) const {
  if (authorization.empty())
    return absl::UnauthenticatedError(
        "this server needs 'authorization: Bearer <token>' metadata (aperture: --token-file or "
        "APERTURE_TOKEN)");
  if (!absl::StartsWith(authorization, kBearer))
    return absl::UnauthenticatedError("authorization metadata must be 'Bearer <token>'");
  const absl::string_view token = absl::StripAsciiWhitespace(authorization.substr(kBearer.size()));
  const std::string digest = Sha256Hex(std::string_view(token.data(), token.size()));
  std::shared_ptr<const std::set<std::string>> digests;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    digests = digests_;
  }
  if (digests->count(digest) == 0) return absl::UnauthenticatedError("the token is not accepted");
  return absl::OkStatus();
}

absl::Status AuthTokens::Check(const grpc::ServerContext& context) const {
  const auto& metadata = context.client_metadata();
  const auto found = metadata.find("authorization");
  if (found == metadata.end()) return CheckHeader("");
  return CheckHeader(absl::string_view(found->second.data(), found->second.size()));
}

}  // namespace aperture
