// Per-frame scene updates on a real server: a stream's updates change the pixels
// exactly as a fresh LoadScene of the changed scene would, they hold from their frame on (also
// through skipped frames), bad ones are answered per frame, and RenderFrame applies one to its
// own frame only.
#include <gmock/gmock.h>
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include <cmath>

#include "integration/service_fixture.h"
#include "scene/demo_scene.h"

namespace aperture::testing {
namespace {

using ::testing::HasSubstr;

// Where the demo's aircraft goes and what the sky and fog become in the tests.
struct DemoState {
  // As the demo loads it.
  double x = 0, y = DemoAircraftAt(0).translation().y(), z = DemoAircraftAt(0).translation().z();
  double yaw = 0;
  bool hidden = false;
  float sky_red = -1;     // < 0: as built
  double visibility = 0;  // 0: as built
};

v1::Transform AircraftTransform(const DemoState& s) {
  v1::Transform t;
  t.mutable_translation()->set_x(s.x);
  t.mutable_translation()->set_y(s.y);
  t.mutable_translation()->set_z(s.z);
  t.set_yaw_deg(s.yaw);
  return t;
}

// The demo scene as a fresh LoadScene of the changed scene would hold it.
v1::Scene DemoIn(const DemoState& s) {
  v1::Scene scene = MakeDemoScene();
  for (v1::Object& o : *scene.mutable_objects()) {
    if (o.name() != kDemoAircraft) continue;
    *o.mutable_transform() = AircraftTransform(s);
    o.set_hidden(s.hidden);
  }
  if (s.sky_red >= 0) scene.mutable_sky()->set_r(s.sky_red);
  if (s.visibility > 0) {
    scene.mutable_fog()->set_density(0);
    scene.mutable_fog()->set_visibility(s.visibility);
  }
  return scene;
}

v1::ObjectUpdate* MoveAircraft(v1::SceneUpdate* update, const DemoState& s) {
  v1::ObjectUpdate* o = update->add_objects();
  o->set_name(kDemoAircraft);
  *o->mutable_transform() = AircraftTransform(s);
  return o;
}

class LiveUpdateTest : public ServiceTest {
 protected:
  // A small frame close behind the aircraft, so that it fills a good part of the view.
  v1::RenderFrameRequest Near(const std::string& scene_id, uint64_t index) const {
    v1::RenderFrameRequest request = FrameRequest(scene_id, 96, 54);
    request.mutable_camera()->mutable_position()->set_y(10);
    request.mutable_camera()->mutable_position()->set_z(120);
    request.set_frame_index(index);
    return request;
  }
  // What RenderFrame gives for a fresh load of the demo in state `s`.
  std::vector<float> Fresh(const DemoState& s) {
    v1::RenderFrameResponse response;
    const grpc::Status status = Render(Near(LoadScene(DemoIn(s)), 0), 30, &response);
    EXPECT_TRUE(status.ok()) << status.error_message();
    return Pixels(response);
  }
};

TEST_F(LiveUpdateTest, StreamUpdatesEqualAFreshLoadOfTheChangedScene) {
  StartServer();
  const std::string scene_id = LoadDemoScene();
  std::vector<DemoState> states(4);
  states[0].x = -6, states[0].z = 70, states[0].yaw = 25;  // moved
  states[1] = states[0];                                   // no update: it stays
  states[2] = states[1], states[2].sky_red = 0.9f, states[2].visibility = 400;
  states[3] = states[2], states[3].hidden = true;
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(60));
  auto stream = stub_->RenderStream(&context);
  std::vector<v1::RenderFrameResponse> frames;
  for (size_t i = 0; i < states.size(); ++i) {
    v1::RenderFrameRequest request = Near(scene_id, i);
    if (i == 0) MoveAircraft(request.mutable_update(), states[0]);
    if (i == 2) {
      request.mutable_update()->mutable_sky()->set_r(0.9f);
      request.mutable_update()->mutable_sky()->set_g(0);
      request.mutable_update()->mutable_sky()->set_b(0);
      request.mutable_update()->mutable_fog()->set_visibility(400);
      *request.mutable_update()->mutable_fog()->mutable_color() = MakeDemoScene().fog().color();
    }
    if (i == 3) {
      v1::ObjectUpdate* o = request.mutable_update()->add_objects();
      o->set_name(kDemoAircraft);
      o->set_visibility(v1::VISIBILITY_HIDDEN);
    }
    // One at a time, so that none is skipped.
    ASSERT_TRUE(stream->Write(request));
    v1::RenderFrameResponse response;
    ASSERT_TRUE(stream->Read(&response));
    frames.push_back(response);
  }
  stream->WritesDone();
  ASSERT_TRUE(stream->Finish().ok());
  const std::vector<float> unmoved = Fresh(DemoState{});
  for (size_t i = 0; i < states.size(); ++i) {
    ASSERT_EQ(frames[i].status_code(), 0) << frames[i].status_message();
    ASSERT_EQ(frames[i].outcome(), v1::FRAME_OUTCOME_RENDERED);
    DemoState s = states[i];
    v1::Scene expected = DemoIn(s);
    if (s.sky_red >= 0) expected.mutable_sky()->set_g(0), expected.mutable_sky()->set_b(0);
    v1::RenderFrameResponse fresh;
    ASSERT_TRUE(Render(Near(LoadScene(expected), 0), 30, &fresh).ok());
    const std::vector<float> pixels = Pixels(frames[i]);
    ASSERT_FALSE(pixels.empty());
    EXPECT_EQ(pixels, Pixels(fresh)) << "frame " << i;
    EXPECT_NE(pixels, unmoved) << "frame " << i;  // each state shows
  }
}

TEST_F(LiveUpdateTest, BadUpdatesAreAnsweredPerFrameAndChangeNothing) {
  StartServer();
  const std::string scene_id = LoadDemoScene();
  DemoState moved;
  moved.x = 4, moved.z = 60, moved.yaw = -15;
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(60));
  auto stream = stub_->RenderStream(&context);
  std::vector<v1::RenderFrameRequest> requests(4, Near(scene_id, 0));
  MoveAircraft(requests[0].mutable_update(), moved);
  requests[1].mutable_update()->add_objects()->set_name("glider");  // not in the scene
  MoveAircraft(requests[2].mutable_update(), DemoState{})->mutable_transform()->set_yaw_deg(NAN);
  requests[3].mutable_update()->mutable_fog()->set_density(-1);
  std::vector<v1::RenderFrameResponse> frames;
  for (size_t i = 0; i < requests.size(); ++i) {
    requests[i].set_frame_index(i);
    ASSERT_TRUE(stream->Write(requests[i]));
    v1::RenderFrameResponse response;
    ASSERT_TRUE(stream->Read(&response));
    frames.push_back(response);
  }
  // Then a frame without update: still the first update's state.
  v1::RenderFrameRequest last = Near(scene_id, 9);
  ASSERT_TRUE(stream->Write(last));
  v1::RenderFrameResponse after;
  ASSERT_TRUE(stream->Read(&after));
  stream->WritesDone();
  ASSERT_TRUE(stream->Finish().ok());
  EXPECT_EQ(frames[0].status_code(), 0) << frames[0].status_message();
  const char* named[] = {"", "update.objects[0] ('glider'): no object",
                         "transform angles are not finite", "update.fog.density"};
  for (size_t i = 1; i < frames.size(); ++i) {
    EXPECT_EQ(frames[i].status_code(), static_cast<int>(grpc::StatusCode::INVALID_ARGUMENT));
    EXPECT_THAT(frames[i].status_message(), HasSubstr(named[i]));
    EXPECT_TRUE(frames[i].exr().empty());
  }
  EXPECT_EQ(after.status_code(), 0) << after.status_message();
  EXPECT_EQ(Pixels(after), Pixels(frames[0]));
  EXPECT_EQ(Pixels(after), Fresh(moved));
}

// A burst to a slow server: most requests are skipped, but every update still holds from its
// frame on, so the newest frame shows the state all of them make together.
TEST_F(LiveUpdateTest, SkippedFramesKeepTheirUpdates) {
  StartServer({"--threads=1"});
  const std::string scene_id = LoadDemoScene();
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(120));
  auto stream = stub_->RenderStream(&context);
  v1::RenderFrameRequest slow = FrameRequest(scene_id, 1920, 1080);  // keeps the rest waiting
  slow.set_frame_index(0);
  ASSERT_TRUE(stream->Write(slow));
  DemoState s;
  constexpr int kFrames = 12;
  for (int i = 1; i <= kFrames; ++i) {
    v1::RenderFrameRequest request = Near(scene_id, static_cast<uint64_t>(i));
    if (i <= 6) {  // the aircraft taxis, turning
      s.z -= 2, s.yaw += 5;
      MoveAircraft(request.mutable_update(), s);
    }
    if (i == 8) request.mutable_update()->mutable_sky()->set_r(0.8f);
    ASSERT_TRUE(stream->Write(request));
  }
  stream->WritesDone();
  const std::vector<v1::RenderFrameResponse> frames = ReadAllAnswers(*stream);
  ASSERT_TRUE(stream->Finish().ok());
  ASSERT_EQ(frames.size(), static_cast<size_t>(kFrames + 1));
  int skipped = 0;
  for (const v1::RenderFrameResponse& f : frames) {
    EXPECT_EQ(f.status_code(), 0) << f.status_message();
    skipped += f.outcome() != v1::FRAME_OUTCOME_RENDERED;
  }
  EXPECT_GE(skipped, kFrames / 2);
  ASSERT_EQ(frames.back().outcome(), v1::FRAME_OUTCOME_RENDERED);
  v1::Scene expected = DemoIn(s);
  expected.mutable_sky()->set_r(0.8f);
  expected.mutable_sky()->set_g(0);
  expected.mutable_sky()->set_b(0);
  v1::RenderFrameResponse fresh;
  ASSERT_TRUE(Render(Near(LoadScene(expected), 0), 30, &fresh).ok());
  EXPECT_EQ(Pixels(frames.back()), Pixels(fresh));
}

TEST_F(LiveUpdateTest, RenderFrameAppliesAnUpdateToItsFrameOnly) {
  StartServer();
  const std::string scene_id = LoadDemoScene();
  DemoState hidden;
  hidden.hidden = true;
  v1::RenderFrameRequest request = Near(scene_id, 0);
  v1::ObjectUpdate* o = request.mutable_update()->add_objects();
  o->set_name(kDemoAircraft);
  o->set_visibility(v1::VISIBILITY_HIDDEN);
  v1::RenderFrameResponse with_update, without;
  ASSERT_TRUE(Render(request, 30, &with_update).ok());
  EXPECT_EQ(Pixels(with_update), Fresh(hidden));
  ASSERT_TRUE(Render(Near(scene_id, 1), 30, &without).ok());
  EXPECT_EQ(Pixels(without), Fresh(DemoState{}));
  EXPECT_NE(Pixels(without), Pixels(with_update));
  request.mutable_update()->mutable_objects(0)->set_name("nope");
  const grpc::Status bad = Render(request, 30);
  EXPECT_EQ(bad.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(bad.error_message(), HasSubstr("'nope'"));
}

}  // namespace
}  // namespace aperture::testing
