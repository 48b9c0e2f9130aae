// Renders the built-in demo airfield through an installed Aperture engine and writes it as EXR:
// `render_demo OUT.exr` prints "WIDTHxHEIGHT, N bytes, M of P pixels lit" and exits 0 when the
// frame has both sky and lit ground.
#include <aperture/io/exr_writer.h>
#include <aperture/render/frame_renderer.h>
#include <aperture/scene/demo_scene.h>
#include <aperture/scene/scene_builder.h>

#include <cstdio>
#include <fstream>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: render_demo OUT.exr\n");
    return 2;
  }
  auto scene = aperture::BuildScene(aperture::MakeDemoScene());
  if (!scene.ok()) {
    std::fprintf(stderr, "render_demo: %s\n", std::string(scene.status().message()).c_str());
    return 1;
  }
  aperture::RenderSettings settings;
  settings.width = 96;
  settings.height = 54;
  auto frame = aperture::RenderFrame(*scene, aperture::DemoCamera(), settings);
  if (!frame.ok()) {
    std::fprintf(stderr, "render_demo: %s\n", std::string(frame.status().message()).c_str());
    return 1;
  }
  auto bytes = aperture::EncodeExr(frame->image, aperture::ExrOptions{});
  if (!bytes.ok()) return 1;
  std::ofstream(argv[1], std::ios::binary) << *bytes;
  // The demo's camera sees sky above the horizon and the textured airfield below it.
  const aperture::Rgba top = frame->image.at(48, 0), bottom = frame->image.at(48, 53);
  int differing = 0;
  for (int y = 0; y < 54; ++y)
    for (int x = 0; x < 96; ++x)
      differing += frame->image.at(x, y).r != top.r || frame->image.at(x, y).g != top.g;
  std::printf("96x54, %zu bytes, %d of %d pixels differ from the sky\n", bytes->size(), differing,
              96 * 54);
  return bytes->size() > 0 && differing > 96 * 54 / 4 && bottom.r != top.r ? 0 : 1;
}
