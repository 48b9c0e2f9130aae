// HTTP/2 keepalive of every connection between an aperture client and server (gRPC's keepalive
// guide, doc/keepalive.md): while calls are in flight, each side pings after a minute without
// traffic and drops a connection whose ping is not answered in 20 s, so a simulator's stream or a
// batch's frame does not wait forever on a peer that vanished (a pulled cable, a killed VM). The
// server accepts client pings as often as every 30 s, half the clients' interval: a faster pinger
// is sent GOAWAY ("too_many_pings"). Plain numbers, so the client links no server code.
#pragma once

namespace aperture::keepalive {

inline constexpr int kTimeMs = 60'000;
inline constexpr int kTimeoutMs = 20'000;
inline constexpr int kServerMinPingIntervalMs = 30'000;

}  // namespace aperture::keepalive
