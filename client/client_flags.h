// The command-line flags of `aperture`, shared by its commands (absl flags are global).
#pragma once

#include <cstdint>
#include <string>

#include "absl/flags/declare.h"
#include "absl/status/status.h"
#include "frame_flags.h"  // the frame flags aperture-render shares

ABSL_DECLARE_FLAG(std::string, server);
ABSL_DECLARE_FLAG(std::string, servers);
ABSL_DECLARE_FLAG(std::string, tls_ca);
ABSL_DECLARE_FLAG(std::string, tls_cert);
ABSL_DECLARE_FLAG(std::string, tls_key);
ABSL_DECLARE_FLAG(std::string, token_file);
ABSL_DECLARE_FLAG(bool, allow_any_path);
ABSL_DECLARE_FLAG(int, split);
ABSL_DECLARE_FLAG(double, deadline_s);
ABSL_DECLARE_FLAG(int, concurrency);
ABSL_DECLARE_FLAG(std::string, shard);
ABSL_DECLARE_FLAG(bool, check);
ABSL_DECLARE_FLAG(bool, contact_sheet);
ABSL_DECLARE_FLAG(int, requests);
ABSL_DECLARE_FLAG(double, duration);
ABSL_DECLARE_FLAG(int, repeat);
ABSL_DECLARE_FLAG(bool, json);
ABSL_DECLARE_FLAG(double, rate);
ABSL_DECLARE_FLAG(int, frames);
ABSL_DECLARE_FLAG(std::string, path);
ABSL_DECLARE_FLAG(std::string, channels);
ABSL_DECLARE_FLAG(std::string, last_frames);

namespace aperture {

// The numeric flags within their ranges (--deadline-s > 0, --concurrency >= 1, ...), whichever
// command runs: INVALID_ARGUMENT naming the flag and its value.
absl::Status CheckClientFlags();

}  // namespace aperture
