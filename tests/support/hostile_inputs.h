// Inputs a hostile client sends, shared by the hostile-client tests and the hostile benchmarks:
// a PNG that declares more than it holds, a scene on one textured ground quad, a scene
// of many named objects and the updates that name them all or one of them many times.
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

// A scene of `objects` named objects ("object-0", "object-1", ...), each one small triangle of the
// same mesh, in rows on the ground in front of the origin.
v1::Scene ManyObjectsScene(int objects);

// An update naming each of ManyObjectsScene(objects)'s objects once: every one moved a little,
// every other one also hidden (so the polygon ranges change, not only their contents).
v1::SceneUpdate UpdateEveryObject(int objects);

// An update naming the last of ManyObjectsScene(objects)'s objects `times` times, moving it a
// little each time (the last, so that a search along the objects would be at its longest).
v1::SceneUpdate UpdateOneObjectRepeatedly(int objects, int times);

}  // namespace aperture::testing
