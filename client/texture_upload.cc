#include "texture_upload.h"

#include <algorithm>

#include "channel.h"
#include "content_hash.h"
#include "grpc_status.h"

namespace aperture {

absl::StatusOr<UploadedTexture> EnsureTextureUploaded(v1::Render::Stub& stub,
                                                      const std::string& bytes) {
  UploadedTexture result{Sha256Hex(bytes), false};
  {
    grpc::ClientContext context;
    context.set_deadline(DeadlineIn(30));
    v1::HasTextureRequest request;
    request.set_sha256(result.sha256);
    v1::HasTextureResponse response;
    if (auto s = FromGrpcStatus(stub.HasTexture(&context, request, &response), "HasTexture");
        !s.ok())
      return s;
    if (response.stored()) return result;
  }
  grpc::ClientContext context;
  context.set_deadline(DeadlineIn(300));
  v1::UploadTextureResponse response;
  auto writer = stub.UploadTexture(&context, &response);
  for (size_t offset = 0; offset < bytes.size() || offset == 0; offset += kUploadChunkBytes) {
    v1::UploadTextureRequest chunk;
    if (offset == 0) {
      chunk.set_sha256(result.sha256);
      chunk.set_total_size(bytes.size());
    }
    chunk.set_chunk(bytes.substr(offset, std::min(kUploadChunkBytes, bytes.size() - offset)));
    if (!writer->Write(chunk)) break;  // the server ended the call early; Finish says why
    if (bytes.empty()) break;
  }
  writer->WritesDone();
  if (auto s = FromGrpcStatus(writer->Finish(), "UploadTexture"); !s.ok()) return s;
  result.sent = !response.already_stored();
  return result;
}

}  // namespace aperture
