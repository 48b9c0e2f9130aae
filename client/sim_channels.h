// `aperture sim --channels N`: N display channels side by side, as an image generator drives a
// wall of projectors. Each channel has the base view's size (its vertical field of view and the
// frame's aspect, or its frustum), and their off-axis frusta tile one wide planar view N times as
// wide, all looking where the base camera looks: channel k's right edge is channel k+1's left
// edge, so the frames placed side by side are one picture.
#pragma once

#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "aperture/v1/scene.pb.h"

namespace aperture {

// The frusta of `channels` channels (left to right) for frames of width x height.
absl::StatusOr<std::vector<v1::Frustum>> ChannelFrusta(const v1::Camera& base, int channels,
                                                       uint32_t width, uint32_t height);

}  // namespace aperture
