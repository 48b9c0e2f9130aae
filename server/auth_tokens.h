// Bearer tokens for the service: a file of accepted tokens, one per line,
// read at start and again on SIGHUP. Every RPC of aperture.v1.Render asks `Check` with the call's
// `authorization: Bearer <token>` metadata; gRPC's health service is not ours and stays open.
// Only SHA-256 digests of the tokens are held, so the tokens never reach a log or a core file by
// way of this class, and a lookup's timing says nothing about how much of a guess was right.
#pragma once

#include <grpcpp/server_context.h>

#include <memory>
#include <mutex>
#include <set>
#include <string>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"

namespace aperture {

class AuthTokens {
 public:
  // Reads `path`; an unreadable file or one without a token is an error naming the file.
  static absl::StatusOr<std::unique_ptr<AuthTokens>> Load(const std::string& path);

  // Reads the file again. On error the tokens accepted so far stay (a half-edited file does not
  // lock every client out); returns how many tokens are accepted now.
  absl::StatusOr<size_t> Reload();

  // OK when the call carries `authorization: Bearer <token>` with an accepted token, else
  // UNAUTHENTICATED saying what was missing (never echoing what was sent).
  absl::Status Check(const grpc::ServerContext& context) const;
  absl::Status CheckHeader(absl::string_view authorization) const;

  const std::string& path() const { return path_; }

 private:
  explicit AuthTokens(std::string path) : path_(std::move(path)) {}
  static absl::StatusOr<std::set<std::string>> ReadDigests(const std::string& path);

  const std::string path_;
  mutable std::mutex mutex_;
  std::shared_ptr<const std::set<std::string>> digests_;  // SHA-256 hex of each token
};

}  // namespace aperture
