// The EXR compression `aperture sim` asks for when --compression is not given. A server on this
// machine (a loopback address, a Unix socket) gets zip, the client's default for every command:
// lossless, and the bytes cost nothing to move. A server across a network gets b44a, OpenEXR's
// real-time playback codec: the fastest encode of the codecs that bring a 30 Hz stream of the
// airport within a 1 GbE link at 1280x720 and 1920x1080, its size bounded whatever the content
// (at most 45 of 128 bytes per 4 x 4 block of an opaque frame), its error far below what a
// display shows (docs/SERVICE.md, "Compression for a remote server"; docs/BENCHMARKS.md). Float
// pixels, which b44a does not compress, keep zip.
#pragma once

#include "absl/strings/string_view.h"
#include "aperture/v1/scene.pb.h"

namespace aperture {

// Whether a gRPC target names this machine: localhost, 127.0.0.0/8 or [::1] (with or without
// gRPC's dns:, ipv4: or ipv6: scheme), or a unix: socket.
bool IsLoopbackTarget(absl::string_view target);

// zip for a loopback target or float pixels, b44a for half pixels from any other target.
v1::ExrCompression SimDefaultCompression(absl::string_view target, v1::PixelType pixel_type);

}  // namespace aperture
