// The command-line flags of `aperture`, shared by its commands (absl flags are global).
#pragma once

#include <cstdint>
#include <string>

#include "absl/flags/declare.h"

ABSL_DECLARE_FLAG(std::string, server);
ABSL_DECLARE_FLAG(std::string, servers);
ABSL_DECLARE_FLAG(std::string, tls_ca);
ABSL_DECLARE_FLAG(std::string, tls_cert);
ABSL_DECLARE_FLAG(std::string, tls_key);
ABSL_DECLARE_FLAG(std::string, token_file);
ABSL_DECLARE_FLAG(bool, allow_any_path);
ABSL_DECLARE_FLAG(int, split);
ABSL_DECLARE_FLAG(std::string, scene);
ABSL_DECLARE_FLAG(std::string, camera);
ABSL_DECLARE_FLAG(double, fov);
ABSL_DECLARE_FLAG(double, near);
ABSL_DECLARE_FLAG(std::string, size);
ABSL_DECLARE_FLAG(std::string, region);
ABSL_DECLARE_FLAG(std::string, aa);
ABSL_DECLARE_FLAG(std::string, filter);
ABSL_DECLARE_FLAG(double, aperture);
ABSL_DECLARE_FLAG(std::string, mode);
ABSL_DECLARE_FLAG(double, delta);
ABSL_DECLARE_FLAG(int, max_depth);
ABSL_DECLARE_FLAG(std::string, compression);
ABSL_DECLARE_FLAG(bool, float_pixels);
ABSL_DECLARE_FLAG(bool, transparent_sky);
ABSL_DECLARE_FLAG(std::string, o);
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
ABSL_DECLARE_FLAG(int, channels);
ABSL_DECLARE_FLAG(std::string, last_frames);
