#include "byte_budget.h"

#include "absl/strings/str_cat.h"

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
  if (bytes > limit_)
    return absl::ResourceExhaustedError(absl::StrCat("this request alone needs ", MiB(bytes),
                                                     ", above the budget of ", what_, ", ",
                                                     MiB(limit_)));
  if (used_ + bytes > limit_)
    return absl::ResourceExhaustedError(absl::StrCat(what_, ": ", MiB(used_), " of ", MiB(limit_),
                                                     " in use, ", MiB(bytes),
                                                     " more do not fit; try again later"));
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
