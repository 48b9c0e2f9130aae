#include "byte_budget.h"

#include "absl/strings/str_cat.h"
#include "refusal_log.h"

namespace aperture {
namespace {

std::string MiB(uint64_t bytes) { return absl::StrCat(bytes / double(1 << 20), " MiB"); }

}  // namespace

ByteReservation& ByteReservation::operator=(ByteReservation&& other) noexcept {
  if (this != &other) {
    Release();
    budget_ = other.budget_;
    bytes_ = other.bytes_;
    other.budget_ = nullptr;
    other.bytes_ = 0;
  }
  return *this;
}

void ByteReservation::Release() {
  if (budget_ != nullptr) budget_->Return(bytes_);
  budget_ = nullptr;
  bytes_ = 0;
}

absl::StatusOr<ByteReservation> ByteBudget::Reserve(uint64_t bytes) {
  std::lock_guard<std::mutex> lock(mutex_);
  const std::string kind = absl::StrCat("over the budget of ", what_);
  if (bytes > limit_)
    return MarkRefusal(absl::ResourceExhaustedError(
                           absl::StrCat("this request alone needs ", MiB(bytes),
                                        ", above the budget of ", what_, ", ", MiB(limit_))),
                       kind);
  if (used_ + bytes > limit_)
    return MarkRefusal(absl::ResourceExhaustedError(
                           absl::StrCat(what_, ": ", MiB(used_), " of ", MiB(limit_), " in use, ",
                                        MiB(bytes), " more do not fit; try again later")),
                       kind);
  used_ += bytes;
  return ByteReservation(this, bytes);
}

uint64_t ByteBudget::used() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return used_;
}

void ByteBudget::Return(uint64_t bytes) {
  std::lock_guard<std::mutex> lock(mutex_);
  used_ -= bytes;
}

}  // namespace aperture
