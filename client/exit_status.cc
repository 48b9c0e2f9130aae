#include "exit_status.h"

#include <cstdio>
#include <string>

#include "absl/strings/cord.h"

namespace aperture {
namespace {

// The payload InputError sets: a type URL of this client's own.
constexpr char kInputErrorUrl[] = "type.aperture.dev/client.InputError";

}  // namespace

absl::Status InputError(absl::Status status) {
  if (!status.ok()) status.SetPayload(kInputErrorUrl, absl::Cord("input"));
  return status;
}

bool IsInputError(const absl::Status& status) {
  return status.GetPayload(kInputErrorUrl).has_value();
}

int ExitStatus(const absl::Status& status) {
  if (status.ok()) return 0;
  return IsInputError(status) || absl::IsInvalidArgument(status) ? 2 : 1;
}

int Fail(const char* command, const absl::Status& status) {
  std::fprintf(stderr, "aperture %s: error: %s\n", command, std::string(status.message()).c_str());
  return ExitStatus(status);
}

}  // namespace aperture
