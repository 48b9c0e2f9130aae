// The decompressed bytes of one zstd frame, read in order a chunk at a time: the .apv reader keeps
// only the runs it has parsed, however much a small compressed block claims to hold.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "absl/status/status.h"

namespace aperture::packed {

// The largest zstd window a run block may use (16 MiB): the writer's levels stay below it, and a
// hostile frame header cannot make the reader reserve more.
inline constexpr int kApvZstdWindowLogMax = 24;

// Compresses `bytes` as one zstd frame (level clamped to 1..19, whose windows fit the reader's).
std::vector<uint8_t> ZstdCompressFrame(std::span<const uint8_t> bytes, int level);

class ZstdFrameReader {
 public:
  // `frame`: the compressed bytes, exactly one frame; `declared_size`: what the header says the
  // frame decompresses to (reading past it is an error).
  ZstdFrameReader(std::span<const uint8_t> frame, uint64_t declared_size);
  ~ZstdFrameReader();
  ZstdFrameReader(const ZstdFrameReader&) = delete;
  ZstdFrameReader& operator=(const ZstdFrameReader&) = delete;

  // The next decompressed byte; false at the frame's end or on an error (status() tells which).
  bool Next(uint8_t& byte) {
    if (pos_ < filled_) {
      byte = chunk_[pos_++];
      return true;
    }
    return Refill(byte);
  }
  // OK, or why decompression stopped: a corrupt or truncated frame, more bytes than declared.
  const absl::Status& status() const { return status_; }
  // After the last byte the reader needed: OK only when the frame ends there, with exactly the
  // declared size, and no bytes follow it.
  absl::Status Finish();

 private:
  bool Refill(uint8_t& byte);

  struct FreeContext {
    void operator()(void* context) const;
  };
  std::unique_ptr<void, FreeContext> context_;
  std::span<const uint8_t> frame_;
  size_t consumed_ = 0;  // compressed bytes the decoder has taken
  uint64_t declared_size_;
  uint64_t produced_ = 0;
  bool frame_done_ = false;
  absl::Status status_;
  std::unique_ptr<uint8_t[]> chunk_;
  size_t pos_ = 0, filled_ = 0;
};

}  // namespace aperture::packed
