#include "client_flags.h"

#include <cmath>

#include "absl/flags/flag.h"
#include "absl/strings/str_cat.h"

ABSL_FLAG(std::string, server, "127.0.0.1:50051", "server address HOST:PORT");
ABSL_FLAG(std::string, tls_ca, "",
          "PEM file of the certificate authority (or the server's self-signed certificate) to "
          "trust; set: connect with TLS, else plaintext");
ABSL_FLAG(std::string, tls_cert, "",
          "PEM certificate of this client, for a server that requires client certificates "
          "(--tls-client-ca); needs --tls-ca and --tls-key");
ABSL_FLAG(std::string, tls_key, "", "PEM private key of --tls-cert");
ABSL_FLAG(bool, allow_any_path, false,
          "upload texture files a scene file names outside its own folder (by default a path "
          "that resolves, symlinks followed, outside the scene file's folder is refused)");
ABSL_FLAG(std::string, token_file, "",
          "file whose first line is the bearer token for a server started with --auth-tokens "
          "(default: the APERTURE_TOKEN environment variable, if set)");
ABSL_FLAG(std::string, servers, "127.0.0.1:50051",
          "batch: servers HOST:PORT,... (gRPC round_robin over them); a host name stands for all "
          "of its IPv4 addresses (a headless Service: every pod behind it); sim: the servers the "
          "channels render on, channel k on server k mod their number (default: --server)");
ABSL_FLAG(int, split, 0,
          "render: cut the frame into this many regions of equal predicted cost (PlanRegions) "
          "and render them on --servers at once, then assemble one EXR (0: one server)");
ABSL_FLAG(double, deadline_s, 60, "deadline of each frame request, seconds");
ABSL_FLAG(int, concurrency, 1, "load, batch: requests in flight at once");
ABSL_FLAG(std::string, shard, "",
          "batch: render only shard I/N of the job, the frames f with f mod N = I (for job arrays: "
          "--shard $JOB_COMPLETION_INDEX/N, --shard $SLURM_ARRAY_TASK_ID/N); empty: every frame");
ABSL_FLAG(
    bool, contact_sheet, true,
    "batch: write contact_sheet.png (thumbnails with frame numbers) next to the frames at the end");
ABSL_FLAG(bool, check, false,
          "batch: render nothing, contact no server: read back every frame of the job (or of "
          "--shard) and list those missing or invalid; exit 0 only when all are valid");
ABSL_FLAG(int, requests, 0, "load: total requests (0: run for --duration)");
ABSL_FLAG(double, duration, 10, "load: seconds to run when --requests is 0");
ABSL_FLAG(int, repeat, 1,
          "render: request the frame this many times on one connection, a line each (benchmarks); "
          "the last is written");
ABSL_FLAG(bool, json, false, "load, sim: print the summary as JSON");
ABSL_FLAG(double, rate, 30, "sim: frames per second");
ABSL_FLAG(int, frames, 100, "sim: frames to request");
ABSL_FLAG(std::string, path, "",
          "sim: path file, per line a camera X,Y,Z,YAW,PITCH,ROLL or a JSON RenderFrameRequest "
          "with camera and scene update (docs/SERVICE.md; default: flying along -z at 60 m/s, the "
          "scene's named objects rolling forward)");
ABSL_FLAG(std::string, channels, "1",
          "sim: display channels, each its own stream locked to the others by frame number: N "
          "(planar off-axis tiles of one wide view), NxW or NxWxV (N channels W degrees wide, V "
          "high, turned around the eye: 3x60 spans 180 degrees), or a channel-set file "
          "(aperture.v1.ChannelSet in text format; docs/SERVICE.md)");
ABSL_FLAG(std::string, last_frames, "",
          "sim: write each channel's last rendered frame to DIR/channel-K.exr");

namespace aperture {

absl::Status CheckClientFlags() {
  auto bad = [](const char* flag, auto value, const char* range) {
    return absl::InvalidArgumentError(absl::StrCat(flag, " is ", value, "; it must be ", range));
  };
  const double deadline = absl::GetFlag(FLAGS_deadline_s);
  if (!(deadline > 0) || !std::isfinite(deadline))
    return bad("--deadline-s", deadline, "a positive number of seconds");
  if (const int n = absl::GetFlag(FLAGS_concurrency); n < 1)
    return bad("--concurrency", n, "at least 1");
  if (const int n = absl::GetFlag(FLAGS_repeat); n < 1) return bad("--repeat", n, "at least 1");
  if (const int n = absl::GetFlag(FLAGS_requests); n < 0)
    return bad("--requests", n, "0 (run for --duration) or more");
  const double duration = absl::GetFlag(FLAGS_duration);
  if (!(duration > 0) || !std::isfinite(duration))
    return bad("--duration", duration, "a positive number of seconds");
  const double rate = absl::GetFlag(FLAGS_rate);
  if (!(rate > 0) || !std::isfinite(rate)) return bad("--rate", rate, "a positive rate in Hz");
  if (const int n = absl::GetFlag(FLAGS_frames); n < 1) return bad("--frames", n, "at least 1");
  if (const int n = absl::GetFlag(FLAGS_split); n < 0)
    return bad("--split", n, "0 (one server) or more");
  return absl::OkStatus();
}

}  // namespace aperture
