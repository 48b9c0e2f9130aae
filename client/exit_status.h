// The exit status of a command (docs/SERVICE.md, "Exit status"): 0 success; 2 bad input - a flag,
// a file the command reads, the server's address (a name that does not resolve, nothing answering
// there) - or a request the server refused as invalid (INVALID_ARGUMENT); 1 the server refused or
// failed otherwise (busy, not found, shutting down, ...).
#pragma once

#include "absl/status/status.h"

namespace aperture {

// `status` marked as caused by the command's input: its exit status is 2 whatever its code.
absl::Status InputError(absl::Status status);
bool IsInputError(const absl::Status& status);

int ExitStatus(const absl::Status& status);

// Prints "aperture COMMAND: error: MESSAGE" to stderr and returns ExitStatus(status).
int Fail(const char* command, const absl::Status& status);

}  // namespace aperture
