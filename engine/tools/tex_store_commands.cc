// aperture-tex subcommands for the machine's shared texture store (engine/store): bake fills it
// ahead of time, store lists what it holds.
#include <cstdio>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "base/stopwatch.h"
#include "render/trace_renderer.h"
#include "scene/builtin_scenes.h"
#include "scene/scene_builder.h"
#include "scene/scene_file.h"
#include "store/shared_store.h"
#include "tools/tex_commands.h"

namespace aperture {
namespace {

int Fail(const char* command, const std::string& message) {
  std::fprintf(stderr, "aperture-tex %s: %s\n", command, message.c_str());
  return 2;
}

struct StoreArgs {
  std::vector<std::string> positional;
  std::string store = kDefaultStoreDirectory;
  bool help = false;
  bool raytrace = false;  // bake: also seed 003's summed-area tables
};

absl::StatusOr<StoreArgs> ParseStoreArgs(int argc, char** argv) {
  StoreArgs args;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      args.help = true;
    } else if (a == "--raytrace") {
      args.raytrace = true;
    } else if (a == "--store") {
      if (i + 1 >= argc) return absl::InvalidArgumentError("--store needs a directory");
      args.store = argv[++i];
    } else if (a.rfind("--store=", 0) == 0) {
      args.store = a.substr(8);
    } else if (a.rfind("-", 0) == 0 && a.size() > 1) {
      return absl::InvalidArgumentError(absl::StrCat("unknown option '", a, "'"));
    } else {
      args.positional.push_back(a);
    }
  }
  return args;
}

absl::StatusOr<Scene> LoadForBake(const std::string& argument,
                                  std::shared_ptr<const SharedStore> store) {
  auto builtin = FindBuiltinScene(argument);
  if (!builtin.ok()) return LoadSceneFile(argument, std::move(store));
  SceneBuildOptions options;
  options.store = std::move(store);
  return BuildScene(builtin->scene, options);
}

// ---- bake ------------------------------------------------------------------------------------

int RunBake(int argc, char** argv) {
  auto args = ParseStoreArgs(argc, argv);
  if (!args.ok()) return Fail("bake", std::string(args.status().message()));
  if (args->help || args->positional.empty()) {
    std::fprintf(args->help ? stdout : stderr,
                 "usage: aperture-tex bake SCENE.json|demo|triangles|skewed ... [--store DIR]\n"
                 "         [--raytrace]\n"
                 "Fills the shared texture store (default %s) with every table and packed\n"
                 "texture the scenes use, so servers map them at once instead of building them;\n"
                 "--raytrace: also the summed-area tables of the raytrace mode (64 bytes per\n"
                 "texel and channel, and a third more for the mip levels).\n"
                 "Entries already there are checked and kept; broken ones are rebuilt.\n",
                 kDefaultStoreDirectory);
    return args->help ? 0 : 2;
  }
  auto store = SharedStore::Open(args->store);
  if (!store.ok()) return Fail("bake", std::string(store.status().message()));
  const Stopwatch timer;
  for (const std::string& argument : args->positional) {
    // Packed textures are decoded into the store while the scene is built.
    auto scene = LoadForBake(argument, *store);
    if (!scene.ok()) return Fail("bake", std::string(scene.status().message()));
    // Tables of materials filtered aniso were prepared with the scene; the rest are built here,
    // since any request may ask for aniso.
    for (const auto& texture : scene->textures) {
      if (!texture->footprint) continue;
      const Stopwatch texture_timer;
      const Image& base = texture->pyramid->level(0);
      std::printf("%s: texture '%s' (%dx%d): ", argument.c_str(), texture->id.c_str(), base.width(),
                  base.height());
      std::fflush(stdout);  // a 4096^2 table takes a while: show which one is building
      if (auto s = texture->footprint->PrepareAniso(); !s.ok())
        return Fail("bake", absl::StrCat(argument, ": texture '", texture->id, "': ", s.message()));
      std::printf("table ready in %.2f s\n", texture_timer.Seconds());
    }
    if (args->raytrace) {
      const Stopwatch sat_timer;
      auto traced = TracedScene::Build(*scene, *store);
      if (!traced.ok())
        return Fail("bake", absl::StrCat(argument, ": ", traced.status().message()));
      std::printf("%s: summed-area tables ready in %.2f s\n", argument.c_str(),
                  sat_timer.Seconds());
    }
  }
  const StoreCounters counters = (*store)->counters();
  std::printf(
      "bake: %s: %llu entries built, %llu already stored, %llu broken ones replaced, "
      "%.2f s\n",
      args->store.c_str(), static_cast<unsigned long long>(counters.built),
      static_cast<unsigned long long>(counters.attached),
      static_cast<unsigned long long>(counters.rejected), timer.Seconds());
  return 0;
}

// ---- store -----------------------------------------------------------------------------------

int RunStore(int argc, char** argv) {
  auto args = ParseStoreArgs(argc, argv);
  if (!args.ok()) return Fail("store", std::string(args.status().message()));
  if (args->help || !args->positional.empty()) {
    std::fprintf(args->help ? stdout : stderr,
                 "usage: aperture-tex store [--store DIR]\n"
                 "Lists the entries of the shared texture store (default %s): key, bytes, state.\n",
                 kDefaultStoreDirectory);
    return args->help ? 0 : 2;
  }
  auto store = SharedStore::Open(args->store);
  if (!store.ok()) return Fail("store", std::string(store.status().message()));
  uint64_t total = 0;
  const auto entries = (*store)->List();
  for (const StoreEntryInfo& e : entries) {
    std::printf("%-90s %12llu  %s\n", e.key.c_str(), static_cast<unsigned long long>(e.bytes),
                e.state.c_str());
    total += e.bytes;
  }
  std::printf("%zu entries, %llu bytes in %s\n", entries.size(),
              static_cast<unsigned long long>(total), args->store.c_str());
  return 0;
}

}  // namespace

std::vector<TexCommand> StoreCommands() {
  return {
      {"bake", "fill the shared texture store with a scene's tables and packed textures", RunBake},
      {"store", "list the shared texture store's entries", RunStore},
  };
}

}  // namespace aperture
