#include "texture/packed/apv_run_stream.h"

#include <zstd.h>

#include <algorithm>
#include <new>
#include <string>

#include "absl/strings/str_cat.h"

namespace aperture::packed {
namespace {

constexpr size_t kChunkBytes = size_t{1} << 16;

absl::Status Bad(const std::string& what) {
  return absl::InvalidArgumentError(absl::StrCat(".apv: run block: ", what));
}

}  // namespace

std::vector<uint8_t> ZstdCompressFrame(std::span<const uint8_t> bytes, int level) {
  std::vector<uint8_t> out(ZSTD_compressBound(bytes.size()));
  const size_t n =
      ZSTD_compress(out.data(), out.size(), bytes.data(), bytes.size(), std::clamp(level, 1, 19));
  // Compressing into a buffer of ZSTD_compressBound bytes cannot fail but for lack of memory.
  if (ZSTD_isError(n)) throw std::bad_alloc();
  out.resize(n);
  return out;
}

void ZstdFrameReader::FreeContext::operator()(void* context) const {
  ZSTD_freeDCtx(static_cast<ZSTD_DCtx*>(context));
}

ZstdFrameReader::ZstdFrameReader(std::span<const uint8_t> frame, uint64_t declared_size)
    : context_(ZSTD_createDCtx()),
      frame_(frame),
      declared_size_(declared_size),
      chunk_(new uint8_t[kChunkBytes]) {
  if (context_ == nullptr) throw std::bad_alloc();
  ZSTD_DCtx_setParameter(static_cast<ZSTD_DCtx*>(context_.get()), ZSTD_d_windowLogMax,
                         kApvZstdWindowLogMax);
}

ZstdFrameReader::~ZstdFrameReader() = default;

bool ZstdFrameReader::Refill(uint8_t& byte) {
  while (status_.ok() && !frame_done_) {
    ZSTD_inBuffer in{frame_.data(), frame_.size(), consumed_};
    ZSTD_outBuffer out{chunk_.get(), kChunkBytes, 0};
    const size_t hint = ZSTD_decompressStream(static_cast<ZSTD_DCtx*>(context_.get()), &out, &in);
    consumed_ = in.pos;
    if (ZSTD_isError(hint)) {
      status_ = Bad(absl::StrCat("corrupt zstd stream (", ZSTD_getErrorName(hint), ")"));
      return false;
    }
    produced_ += out.pos;
    if (produced_ > declared_size_) {
      status_ = Bad(absl::StrCat("decompresses to more than the ", declared_size_,
                                 " bytes the header declares"));
      return false;
    }
    frame_done_ = hint == 0;
    if (out.pos > 0) {
      pos_ = 1;
      filled_ = out.pos;
      byte = chunk_[0];
      return true;
    }
    if (!frame_done_ && consumed_ == frame_.size()) {
      status_ = Bad(absl::StrCat("compressed stream truncated: its ", frame_.size(),
                                 " bytes end inside the zstd frame, after ", produced_,
                                 " decompressed bytes"));
      return false;
    }
  }
  return false;
}

absl::Status ZstdFrameReader::Finish() {
  uint8_t extra;
  if (Next(extra)) return Bad("decompressed bytes after the last run");
  if (!status_.ok()) return status_;
  if (consumed_ != frame_.size())
    return Bad(absl::StrCat(frame_.size() - consumed_, " compressed bytes after the zstd frame"));
  if (produced_ != declared_size_)
    return Bad(absl::StrCat("decompresses to ", produced_, " bytes, the header declares ",
                            declared_size_));
  return absl::OkStatus();
}

}  // namespace aperture::packed
