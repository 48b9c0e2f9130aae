// Inputs a hostile client sends, shared by the hostile-client tests and the hostile soak
// (issue 23): a PNG that declares more than it holds, and a scene on one textured ground quad.
#pragma once

#include <cstdint>
#include <string>

#include "aperture/v1/render_service.pb.h"

namespace aperture::testing {

// A PNG whose header declares `width` x `height` texels and whose data is a few bytes: the
// shape of a decompression bomb (the header is all a reader looks at first).
std::string PngDeclaring(uint32_t width, uint32_t height);

// A LoadScene request of one 100 m ground quad textured with the upload `sha256` (or, when
// `checkerboard` > 0, a checkerboard of that size), filtered aniso when `aniso`.
v1::LoadSceneRequest TexturedGroundScene(const std::string& sha256, uint32_t checkerboard = 0,
                                         bool aniso = false);

}  // namespace aperture::testing
