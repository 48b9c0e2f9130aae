#include "batch_job.h"

#include <google/protobuf/struct.pb.h>
#include <google/protobuf/util/json_util.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_split.h"
#include "scene_upload.h"

namespace aperture {
namespace {

absl::StatusOr<std::vector<double>> SixNumbers(const std::string& field, const std::string& text) {
  std::vector<std::string> parts = absl::StrSplit(text, ',');
  std::vector<double> values(parts.size());
  bool ok = parts.size() == 6;
  for (size_t i = 0; ok && i < parts.size(); ++i) ok = absl::SimpleAtod(parts[i], &values[i]);
  if (!ok)
    return absl::InvalidArgumentError(
        absl::StrCat(field, " '", text, "' must be X,Y,Z,YAW,PITCH,ROLL"));
  return values;
}

}  // namespace

absl::StatusOr<BatchJob> ReadBatchJob(const std::string& path) {
  std::ifstream in(path);
  if (!in) return absl::NotFoundError(absl::StrCat("cannot read job file ", path));
  std::ostringstream text;
  text << in.rdbuf();
  google::protobuf::Struct json;
  if (auto s = google::protobuf::util::JsonStringToMessage(text.str(), &json); !s.ok())
    return absl::InvalidArgumentError(absl::StrCat(path, ": ", std::string(s.message())));
  const auto& fields = json.fields();
  auto text_field = [&](const char* name) {
    auto it = fields.find(name);
    return it == fields.end() ? std::string() : it->second.string_value();
  };

  BatchJob job;
  if (std::string scene = text_field("scene"); !scene.empty()) {
    // A scene file is relative to the job file; a built-in scene is a name.
    const std::filesystem::path p(scene);
    job.scene = IsBuiltinScene(scene) || p.is_absolute()
                    ? scene
                    : (std::filesystem::path(path).parent_path() / p).string();
  }
  job.size = text_field("size");
  job.filter = text_field("filter");
  if (auto it = fields.find("cameras"); it != fields.end()) {
    for (const auto& camera : it->second.list_value().values()) {
      if (auto v = SixNumbers("cameras[]", camera.string_value()); !v.ok()) return v.status();
      job.cameras.push_back(camera.string_value());
    }
  } else if (auto p = fields.find("path"); p != fields.end()) {
    const auto& path_fields = p->second.struct_value().fields();
    auto get = [&](const char* name) {
      auto f = path_fields.find(name);
      return f == path_fields.end() ? google::protobuf::Value() : f->second;
    };
    auto from = SixNumbers("path.from", get("from").string_value());
    auto to = SixNumbers("path.to", get("to").string_value());
    if (!from.ok()) return from.status();
    if (!to.ok()) return to.status();
    const int frames = static_cast<int>(get("frames").number_value());
    if (frames < 1 || frames > 1000000)
      return absl::InvalidArgumentError("path.frames must be 1..1000000");
    for (int i = 0; i < frames; ++i) {
      const double t = frames == 1 ? 0.0 : static_cast<double>(i) / (frames - 1);
      std::vector<std::string> parts;
      for (int k = 0; k < 6; ++k)
        parts.push_back(absl::StrFormat("%.17g", (*from)[k] + t * ((*to)[k] - (*from)[k])));
      job.cameras.push_back(absl::StrJoin(parts, ","));
    }
  }
  if (job.cameras.empty())
    return absl::InvalidArgumentError(absl::StrCat(path,
                                                   ": the job has no cameras (give "
                                                   "\"cameras\" or \"path\")"));
  return job;
}

absl::StatusOr<Shard> ParseShard(const std::string& text) {
  Shard shard;
  if (text.empty()) return shard;
  std::vector<std::string> parts = absl::StrSplit(text, '/');
  uint64_t index = 0, count = 0;
  if (parts.size() != 2 || !absl::SimpleAtoi(parts[0], &index) ||
      !absl::SimpleAtoi(parts[1], &count) || count < 1 || count > 1000000 || index >= count)
    return absl::InvalidArgumentError(absl::StrCat(
        "--shard '", text, "' must be I/N with 0 <= I < N <= 1000000, e.g. 0/4 (frame f is in ",
        "shard f mod N)"));
  shard.index = index;
  shard.count = count;
  return shard;
}

}  // namespace aperture
