#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "absl/flags/flag.h"
#include "absl/flags/reflection.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "channel.h"
#include "client_flags.h"
#include "commands.h"
#include "exit_status.h"
#include "latency_stats.h"
#include "process_cpu.h"
#include "report_json.h"
#include "request_flags.h"
#include "scene_upload.h"
#include "sim_channels.h"
#include "sim_compression.h"
#include "sim_path.h"
#include "transport_delay.h"

namespace aperture {
namespace {

using Clock = std::chrono::steady_clock;

// What one channel's stream got.
struct ChannelReport {
  size_t frames = 0, received = 0, dropped = 0, late = 0, skipped = 0;
  LatencySummary latency;
  TransportDelay transport;
  // Median latency of the rendered frames among the first and the last fifth of the frames sent:
  // equal when no backlog builds.
  double first_fifth_p50 = 0, last_fifth_p50 = 0;
  double achieved_hz = 0;
  grpc::Status status;
  v1::RenderFrameResponse last;  // the last rendered frame (--last_frames)
  // When each frame number's frame was complete (its last byte received); empty: not rendered.
  std::vector<std::optional<Clock::time_point>> completed;
  size_t last_rendered = 0;  // the frame number of the last rendered frame
};

// A rendered frame's clocks and the server's stages, grouped as the transport delay reports them.
FrameClocks ClocksOf(const v1::RenderFrameResponse& response, uint64_t host_received_ns) {
  const v1::FrameTimings& t = response.timings();
  FrameClocks c;
  c.host_sent_ns = response.host_sent_unix_ns();
  c.server_received_ns = response.server_received_unix_ns();
  c.server_sent_ns = response.server_sent_unix_ns();
  c.host_received_ns = host_received_ns;
  c.wait_ms = t.wait_ms() + t.queue_ms();
  c.render_ms = t.update_ms() + t.setup_ms() + t.raster_ms();
  c.hold_ms = t.hold_ms();
  c.encode_ms = t.encode_ms();
  return c;
}

// One channel: a RenderStream fed one request per slot of the shared clock (slot i carries frame
// number i on every channel: the host's frame counter locks the channels), answers read as they
// come.
ChannelReport RunChannel(v1::Render::Stub& stub, const v1::RenderFrameRequest& base,
                         const std::vector<SimFrame>& path, const SimChannel& channel,
                         Clock::time_point start, Clock::duration slot, bool keep_last) {
  ChannelReport report;
  report.frames = path.size();
  report.completed.resize(path.size());
  grpc::ClientContext context;
  auto stream = stub.RenderStream(&context);
  std::vector<Clock::time_point> sent(path.size());
  std::mutex mutex;
  std::thread writer([&] {
    for (size_t i = 0; i < path.size(); ++i) {
      std::this_thread::sleep_until(start + slot * static_cast<int64_t>(i));
      v1::RenderFrameRequest request = base;
      *request.mutable_camera() = ChannelCamera(path[i].camera, channel);
      request.mutable_options()->set_width(channel.width);
      request.mutable_options()->set_height(channel.height);
      if (path[i].update) *request.mutable_update() = *path[i].update;
      request.set_scene_time_s(path[i].scene_time_s);
      request.set_frame_index(i);
      {
        std::lock_guard lock(mutex);
        sent[i] = Clock::now();
      }
      request.set_host_sent_unix_ns(UnixNanosecondsNow());
      if (!stream->Write(request)) break;
    }
    stream->WritesDone();
  });

  std::vector<double> latencies, first_fifth, last_fifth;
  std::vector<FrameClocks> clocks;
  Clock::time_point last_frame = start;
  v1::RenderFrameResponse response;
  while (stream->Read(&response)) {
    const auto now = Clock::now();
    const uint64_t received_ns = UnixNanosecondsNow();  // its last byte is in
    const size_t i = response.frame_index();
    ++report.received;
    if (response.status_code() != 0 || i >= path.size()) {
      if (report.dropped == 0 && response.status_code() != 0)
        std::fprintf(stderr, "aperture sim: frame %zu failed: %s\n", i,
                     response.status_message().c_str());
      ++report.dropped;
      continue;
    }
    // The server rendered a newer state instead (newest state wins): not an error.
    if (response.outcome() != v1::FRAME_OUTCOME_RENDERED) {
      ++report.skipped;
      continue;
    }
    Clock::time_point sent_at;
    {
      std::lock_guard lock(mutex);
      sent_at = sent[i];
    }
    const double ms = std::chrono::duration<double, std::milli>(now - sent_at).count();
    latencies.push_back(ms);
    report.completed[i] = now;
    report.last_rendered = std::max(report.last_rendered, i);
    if (i * 5 < path.size()) first_fifth.push_back(ms);
    if (i * 5 >= path.size() * 4) last_fifth.push_back(ms);
    last_frame = now;
    clocks.push_back(ClocksOf(response, received_ns));
    // A frame is late when it arrives after the end of its own slot.
    if (now > start + slot * static_cast<int64_t>(i + 1)) ++report.late;
    if (keep_last) report.last = std::move(response);
  }
  writer.join();
  report.status = stream->Finish();
  report.dropped += path.size() - report.received;
  report.latency = Summarize(latencies);
  report.transport = SummarizeTransport(clocks);
  report.first_fifth_p50 = Summarize(first_fifth).p50;
  report.last_fifth_p50 = Summarize(last_fifth).p50;
  // Frames shown per second of the run, from the first slot to the last frame received.
  const double seconds = std::chrono::duration<double>(last_frame - start).count();
  report.achieved_hz = seconds > 0 ? static_cast<double>(report.latency.count) / seconds : 0.0;
  return report;
}

// The channel a host would notice first: the most frames not shown on time, then the slowest.
size_t WorstChannel(const std::vector<ChannelReport>& reports) {
  size_t worst = 0;
  auto badness = [](const ChannelReport& r) {
    return std::pair(r.late + r.dropped + r.skipped + (r.status.ok() ? 0 : r.frames),
                     r.latency.p99);
  };
  for (size_t k = 1; k < reports.size(); ++k)
    if (badness(reports[k]) > badness(reports[worst])) worst = k;
  return worst;
}

// Per frame number every channel rendered: the last channel's completion minus the first's, ms.
std::vector<double> ChannelSkews(const std::vector<ChannelReport>& reports) {
  std::vector<double> skews;
  for (size_t i = 0; i < reports[0].completed.size(); ++i) {
    std::optional<Clock::time_point> first, last;
    bool everywhere = true;
    for (const ChannelReport& r : reports) {
      const auto& t = r.completed[i];
      if (!t) {
        everywhere = false;
        break;
      }
      first = first ? std::min(*first, *t) : *t;
      last = last ? std::max(*last, *t) : *t;
    }
    if (everywhere)
      skews.push_back(std::chrono::duration<double, std::milli>(*last - *first).count());
  }
  return skews;
}

// The channel's figures; SimReport's first fields are SimChannelReport's, field for field.
template <typename Report>
void FillReport(const ChannelReport& r, double rate, Report& out) {
  out.set_frames(static_cast<uint32_t>(r.frames));
  out.set_rate_hz(Rounded(rate));
  out.set_achieved_hz(Rounded(r.achieved_hz));
  out.set_ok(static_cast<uint32_t>(r.latency.count));
  out.set_late(static_cast<uint32_t>(r.late));
  out.set_skipped(static_cast<uint32_t>(r.skipped));
  out.set_dropped(static_cast<uint32_t>(r.dropped));
  *out.mutable_latency_ms() = LatencyReport(r.latency);
  out.set_p50_first_fifth_ms(Rounded(r.first_fifth_p50));
  out.set_p50_last_fifth_ms(Rounded(r.last_fifth_p50));
  out.set_status(r.status.ok() ? "OK" : r.status.error_message());
  *out.mutable_transport_delay_ms() = TransportDelayReport(r.transport);
}

void PrintText(const ChannelReport& r, double rate, const std::string& label) {
  std::printf(
      "%s%zu frames offered at %.2f Hz: %zu rendered (%.2f Hz achieved), %zu late for their slot, "
      "%zu skipped for a newer state, %zu dropped\n",
      label.c_str(), r.frames, rate, r.latency.count, r.achieved_hz, r.late, r.skipped, r.dropped);
  std::printf("%slatency ms: p50 %.2f  p90 %.2f  p99 %.2f  max %.2f\n",
              std::string(label.size(), ' ').c_str(), r.latency.p50, r.latency.p90, r.latency.p99,
              r.latency.max);
  const TransportDelay& t = r.transport;
  std::printf(
      "%stransport delay ms: p50 %.2f  p99 %.2f  max %.2f; medians: request %.2f  wait %.2f  "
      "render %.2f  hold %.2f  encode %.2f  send %.2f%s\n",
      std::string(label.size(), ' ').c_str(), t.delay_ms.p50, t.delay_ms.p99, t.delay_ms.max,
      t.request_ms, t.wait_ms, t.render_ms, t.hold_ms, t.encode_ms, t.send_ms,
      t.unordered > 0 ? absl::StrCat(" (", t.unordered, " frames' clocks out of order)").c_str()
                      : "");
  if (!r.status.ok()) std::printf("stream ended: %s\n", r.status.error_message().c_str());
}

absl::Status WriteLastFrames(const std::vector<ChannelReport>& reports, const std::string& dir) {
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  for (size_t k = 0; k < reports.size(); ++k) {
    if (reports[k].last.exr().empty())
      return absl::UnavailableError(absl::StrCat("channel ", k, " rendered no frame to write"));
    const std::string file = absl::StrCat(dir, "/channel-", k, ".exr");
    std::ofstream out(file, std::ios::binary);
    out.write(reports[k].last.exr().data(),
              static_cast<std::streamsize>(reports[k].last.exr().size()));
    if (!out) return absl::UnavailableError(absl::StrCat("cannot write ", file));
  }
  return absl::OkStatus();
}

// A server the channels render on: its connection, the scene loaded there, the request its
// channels start from.
struct SimServer {
  std::unique_ptr<v1::Render::Stub> stub;
  SceneOnServer scene;
  v1::RenderFrameRequest base;
};

absl::StatusOr<SimServer> PrepareServer(const std::string& address) {
  auto channel = ConnectChannel(address);
  if (!channel.ok()) return channel.status();
  SimServer server;
  server.stub = v1::Render::NewStub(*channel);
  auto scene = LoadSceneOnServer(*server.stub, absl::GetFlag(FLAGS_scene));
  if (!scene.ok()) return scene.status();
  server.scene = std::move(*scene);
  auto base = FrameRequestFromFlags(server.scene);
  if (!base.ok()) return base.status();
  server.base = std::move(*base);
  // Without --compression, the codec suits where the server is (sim_compression.h).
  if (server.base.options().compression() == v1::EXR_COMPRESSION_DEFAULT)
    server.base.mutable_options()->set_compression(
        SimDefaultCompression(address, server.base.options().pixel_type()));
  return server;
}

// --servers when given a value of its own (its default serves batch), else none.
std::vector<std::string> SimServers() {
  const absl::CommandLineFlag* flag = absl::FindCommandLineFlag("servers");
  if (flag == nullptr || flag->CurrentValue() == flag->DefaultValue()) return {};
  return absl::StrSplit(absl::GetFlag(FLAGS_servers), ',', absl::SkipEmpty());
}

}  // namespace

int RunSim() {
  auto fail = [](const absl::Status& status) { return Fail("sim", status); };
  const double rate = absl::GetFlag(FLAGS_rate);  // > 0 (CheckClientFlags)
  const std::string spec = absl::GetFlag(FLAGS_channels);
  // The first channel's server: its scene and request give the eye and the frame size the
  // channels start from (the channels read again with them).
  auto provisional = ParseChannels(spec, v1::Camera(), 1, 1);
  if (!provisional.ok()) return fail(provisional.status());
  AssignServers(*provisional, SimServers(), absl::GetFlag(FLAGS_server));
  const std::string first_address = provisional->front().server;
  std::map<std::string, SimServer> servers;
  auto first = PrepareServer(first_address);
  if (!first.ok()) return fail(first.status());
  const v1::RenderFrameRequest eye = first->base;
  const std::vector<v1::NamedObject> objects = first->scene.objects;
  servers.emplace(first_address, std::move(*first));
  auto parsed = ParseChannels(spec, eye.camera(), eye.options().width(), eye.options().height());
  if (!parsed.ok()) return fail(parsed.status());
  std::vector<SimChannel>& sim_channels = *parsed;
  AssignServers(sim_channels, SimServers(), absl::GetFlag(FLAGS_server));
  for (const SimChannel& c : sim_channels)
    if (!servers.contains(c.server)) {
      auto server = PrepareServer(c.server);
      if (!server.ok()) return fail(server.status());
      servers.emplace(c.server, std::move(*server));
    }
  const int channels = static_cast<int>(sim_channels.size());
  auto path = MakeSimPath(absl::GetFlag(FLAGS_path), eye.camera(), objects,
                          absl::GetFlag(FLAGS_frames), rate);
  if (!path.ok()) return fail(path.status());

  const auto slot =
      std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / rate));
  const auto start = Clock::now() + std::chrono::milliseconds(20);
  const std::string last_frames = absl::GetFlag(FLAGS_last_frames);
  std::vector<ChannelReport> reports(static_cast<size_t>(channels));
  std::vector<std::thread> threads;
  const double cpu_start = ProcessCpuSeconds();
  for (int k = 0; k < channels; ++k)
    threads.emplace_back([&, k] {
      const SimServer& server = servers.at(sim_channels[k].server);
      reports[k] = RunChannel(*server.stub, server.base, *path, sim_channels[k], start, slot,
                              !last_frames.empty());
    });
  for (std::thread& t : threads) t.join();
  size_t rendered = 0;
  for (const ChannelReport& r : reports) rendered += r.latency.count;
  const double host_cpu_ms_per_frame =
      rendered > 0 ? 1000 * (ProcessCpuSeconds() - cpu_start) / static_cast<double>(rendered) : 0;

  const size_t worst = WorstChannel(reports);
  const std::vector<double> skews = ChannelSkews(reports);
  const LatencySummary skew = Summarize(skews);
  if (absl::GetFlag(FLAGS_json)) {
    // The top-level figures are the worst channel's (all of them when there is one channel).
    v1::SimReport report;
    FillReport(reports[worst], rate, report);
    report.set_host_cpu_ms_per_frame(Rounded(host_cpu_ms_per_frame));
    if (channels > 1) {
      report.set_worst_channel(static_cast<uint32_t>(worst));
      for (int k = 0; k < channels; ++k) {
        v1::SimChannelReport& out = *report.add_channels();
        FillReport(reports[k], rate, out);
        out.set_name(sim_channels[k].name);
        out.set_server(sim_channels[k].server);
        out.set_last_frame(static_cast<uint32_t>(reports[k].last_rendered));
      }
      *report.mutable_channel_skew_ms() = LatencyReport(skew);
      report.set_locked_frames(static_cast<uint32_t>(skews.size()));
    }
    std::printf("%s\n", ReportJson(report).c_str());
  } else if (channels == 1) {
    PrintText(reports[0], rate, "");
  } else {
    for (int k = 0; k < channels; ++k)
      PrintText(reports[k], rate,
                absl::StrCat(sim_channels[k].name, " on ", sim_channels[k].server, ": "));
    std::printf("worst channel: %s\n", sim_channels[worst].name.c_str());
    std::printf(
        "skew between channels completing the same frame, ms: p50 %.2f  p99 %.2f  max %.2f "
        "(%zu of %zu frame numbers rendered on every channel)\n",
        skew.p50, skew.p99, skew.max, skews.size(), path->size());
  }
  if (!absl::GetFlag(FLAGS_json))
    std::printf("host CPU per frame rendered: %.2f ms\n", host_cpu_ms_per_frame);
  if (!last_frames.empty())
    if (auto s = WriteLastFrames(reports, last_frames); !s.ok()) return fail(s);
  bool ok = true;
  for (const ChannelReport& r : reports) ok = ok && r.status.ok() && r.dropped == 0;
  return ok ? 0 : 1;
}

}  // namespace aperture
