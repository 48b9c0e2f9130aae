// Uploads a texture image unless the server already has its content (asked by SHA-256 first).
#pragma once

#include <string>

#include "absl/status/statusor.h"
#include "aperture/v1/render_service.grpc.pb.h"

namespace aperture {

constexpr size_t kUploadChunkBytes = 1 << 20;  // well under gRPC's 4 MiB default

struct UploadedTexture {
  std::string sha256;
  bool sent = false;  // false: the server had it, nothing was sent
};

absl::StatusOr<UploadedTexture> EnsureTextureUploaded(v1::Render::Stub& stub,
                                                      const std::string& bytes);

}  // namespace aperture
