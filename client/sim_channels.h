// The display channels of `aperture sim --channels SPEC`, as an image generator drives the
// projectors of a simulator's screen. SPEC is one of:
//   N        N channels side by side whose off-axis frusta tile one wide planar view N times as
//            wide as the base view (its vertical field of view and the frame's aspect, or its
//            frustum), all looking where the base camera looks: channel k's right edge is
//            channel k+1's left edge, so the frames placed side by side are one picture. A planar
//            view stays below 180 degrees wide.
//   NxW      N channels of W degrees each turned around the eye by yaw offsets (left to right,
//            centred on the eye's heading): 3x60 spans 180 degrees, 5x36 too. Each channel's
//            vertical field makes square pixels at --size.
//   NxWxV    the same with a vertical field of V degrees at each channel's centre.
//   FILE     a channel set in protobuf's text format (aperture.v1.ChannelSet,
//            proto/aperture/v1/channel_set.proto): each channel's view offset, field or frustum,
//            size and server.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "aperture/v1/channel_set.pb.h"
#include "aperture/v1/scene.pb.h"

namespace aperture {

struct SimChannel {
  std::string name;
  // What the channel changes of the eye's camera: its view offset, and its frustum when it has
  // one of its own (else the eye's field of view or frustum stays).
  v1::ViewOffset view_offset;
  bool has_frustum = false;
  v1::Frustum frustum;
  uint32_t width = 0, height = 0;
  std::string server;  // empty: assigned by AssignServers
};

// The frusta of `channels` planar channels (left to right) for frames of width x height.
absl::StatusOr<std::vector<v1::Frustum>> ChannelFrusta(const v1::Camera& base, int channels,
                                                       uint32_t width, uint32_t height);

// The channels SPEC names (see above) for an eye seen through `base` at frames of width x height
// (--size); INVALID_ARGUMENT naming --channels, or the file and the field, for bad input.
absl::StatusOr<std::vector<SimChannel>> ParseChannels(const std::string& spec,
                                                      const v1::Camera& base, uint32_t width,
                                                      uint32_t height);

// The channels of a ChannelSet, checked (`source` names it in errors).
absl::StatusOr<std::vector<SimChannel>> ChannelsFromSet(const v1::ChannelSet& set,
                                                        const std::string& source, uint32_t width,
                                                        uint32_t height);

// Every channel's server: its own, else servers[k mod size] when `servers` is not empty, else
// `fallback`.
void AssignServers(std::vector<SimChannel>& channels, const std::vector<std::string>& servers,
                   const std::string& fallback);

// The camera channel `channel` renders when the eye is at `eye`.
v1::Camera ChannelCamera(const v1::Camera& eye, const SimChannel& channel);

}  // namespace aperture
