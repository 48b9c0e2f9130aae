// The OSMesa (llvmpipe) context the peer benchmarks draw with: RGBA, a 24-bit depth buffer, the
// compatibility profile of OpenGL 3.0 (GL_POINTS with point smoothing, fixed-function fog).
#pragma once

#include <GL/osmesa.h>

#include <cstdint>
#include <cstdio>
#include <vector>

namespace aperture::testing {

inline OSMesaContext CreateOsMesaContext() {
  const int attributes[] = {OSMESA_FORMAT,
                            OSMESA_RGBA,
                            OSMESA_DEPTH_BITS,
                            24,
                            OSMESA_PROFILE,
                            OSMESA_COMPAT_PROFILE,
                            OSMESA_CONTEXT_MAJOR_VERSION,
                            3,
                            OSMESA_CONTEXT_MINOR_VERSION,
                            0,
                            0};
  return OSMesaCreateContextAttribs(attributes, nullptr);
}

// A context made current on a 16 x 16 buffer of its own (`dummy`, kept by the caller), for a
// peer that draws into framebuffer objects; null, said on stderr under `who`, when it fails.
inline OSMesaContext CreateCurrentOsMesaContext(const char* who, std::vector<uint32_t>& dummy) {
  OSMesaContext context = CreateOsMesaContext();
  if (context == nullptr) {
    std::fprintf(stderr, "%s: no OSMesa context\n", who);
    return nullptr;
  }
  dummy.assign(16 * 16, 0);
  if (!OSMesaMakeCurrent(context, dummy.data(), GL_UNSIGNED_BYTE, 16, 16)) {
    std::fprintf(stderr, "%s: OSMesaMakeCurrent failed\n", who);
    OSMesaDestroyContext(context);
    return nullptr;
  }
  return context;
}

}  // namespace aperture::testing
