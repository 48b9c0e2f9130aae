// A budget of bytes that requests reserve while they hold memory: uploads in
// flight reserve their announced size for as long as they stream. A reservation that does not
// fit is RESOURCE_EXHAUSTED naming the budget's flag and the figures; it is returned when the
// reservation goes out of scope.
#pragma once

#include <cstdint>
#include <mutex>
#include <string>

#include "absl/status/statusor.h"

namespace aperture {

class ByteBudget;

class ByteReservation {
 public:
  ByteReservation() = default;
  ByteReservation(ByteReservation&& other) noexcept { *this = std::move(other); }
  ByteReservation& operator=(ByteReservation&& other) noexcept;
  ~ByteReservation() { Release(); }
  void Release();
  uint64_t bytes() const { return bytes_; }

 private:
  friend class ByteBudget;
  ByteReservation(ByteBudget* budget, uint64_t bytes) : budget_(budget), bytes_(bytes) {}
  ByteBudget* budget_ = nullptr;
  uint64_t bytes_ = 0;
};

class ByteBudget {
 public:
  // `what` names the budget in errors, e.g. "uploads in flight (--max-upload-inflight-mb)".
  ByteBudget(std::string what, uint64_t limit) : what_(std::move(what)), limit_(limit) {}

  absl::StatusOr<ByteReservation> Reserve(uint64_t bytes);
  uint64_t used() const;
  uint64_t limit() const { return limit_; }

 private:
  friend class ByteReservation;
  void Return(uint64_t bytes);

  const std::string what_;
  const uint64_t limit_;
  mutable std::mutex mutex_;
  uint64_t used_ = 0;
};

}  // namespace aperture
