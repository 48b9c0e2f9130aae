// The compression `aperture sim` asks for without --compression: zip from a server on this
// machine, b44a across a network (client/sim_compression.h), whatever form the target takes.
#include "sim_compression.h"

#include <gtest/gtest.h>

namespace aperture {
namespace {

TEST(SimCompression, LoopbackTargetsInEveryFormAreThisMachine) {
  for (const char* target :
       {"127.0.0.1:50051", "127.1.2.3:7", "localhost:50051", "[::1]:50051", "::1", "127.0.0.1",
        "dns:///localhost:50051", "dns:localhost:50051", "dns://8.8.8.8/127.0.0.1:50051",
        "ipv4:127.0.0.1:50051", "ipv6:[::1]:50051", "unix:/tmp/aperture.sock",
        "unix-abstract:aperture"})
    EXPECT_TRUE(IsLoopbackTarget(target)) << target;
  for (const char* target :
       {"10.0.0.7:50051", "ig-1.sim.example:50051", "dns:///ig-1:50051", "ipv4:192.168.1.5:50051",
        "[2001:db8::1]:50051", "2001:db8::1", "localhost.example:50051", "128.0.0.1:1", ""})
    EXPECT_FALSE(IsLoopbackTarget(target)) << target;
}

TEST(SimCompression, RemoteServersGetB44aAndLoopbackKeepsZip) {
  EXPECT_EQ(SimDefaultCompression("127.0.0.1:50051", v1::PIXEL_TYPE_DEFAULT),
            v1::EXR_COMPRESSION_ZIP);
  EXPECT_EQ(SimDefaultCompression("ig-1:50051", v1::PIXEL_TYPE_DEFAULT), v1::EXR_COMPRESSION_B44A);
  EXPECT_EQ(SimDefaultCompression("ig-1:50051", v1::PIXEL_TYPE_HALF), v1::EXR_COMPRESSION_B44A);
  // b44a compresses half channels only: float frames keep zip rather than fail.
  EXPECT_EQ(SimDefaultCompression("ig-1:50051", v1::PIXEL_TYPE_FLOAT), v1::EXR_COMPRESSION_ZIP);
}

}  // namespace
}  // namespace aperture
