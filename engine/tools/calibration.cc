#include "tools/calibration.h"

#include <algorithm>

#include "cost/rank_correlation.h"
#include "render/frame_renderer.h"

namespace aperture {

absl::StatusOr<CalibrationResult> Calibrate(const std::vector<CalibrationFrame>& frames, int width,
                                            int height, int repeat) {
  std::vector<WindowFeatures> features;
  std::vector<double> times;
  for (const CalibrationFrame& f : frames) {
    RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.threads = 1;
    settings.scheduling.mode = Scheduling::kUniform;
    settings.scheduling.predict_uniform = true;
    std::vector<double> best;
    std::vector<WindowFeatures> frame_features;
    for (int r = 0; r < std::max(1, repeat); ++r) {
      auto frame = RenderFrame(*f.scene, f.camera, settings);
      if (!frame.ok()) return frame.status();
      const auto& tasks = frame->stats.tasks;
      if (best.empty()) {
        best.assign(tasks.size(), 1e300);
        for (const TaskTiming& t : tasks) frame_features.push_back(t.features);
      }
      for (size_t i = 0; i < tasks.size(); ++i) best[i] = std::min(best[i], tasks[i].measured_us);
    }
    features.insert(features.end(), frame_features.begin(), frame_features.end());
    times.insert(times.end(), best.begin(), best.end());
  }
  CalibrationResult result;
  result.model = FitCostModel(features, times);
  result.tiles = static_cast<int>(times.size());
  std::vector<double> predicted;
  for (const WindowFeatures& f : features) predicted.push_back(result.model.Predict(f));
  result.spearman = SpearmanCorrelation(predicted, times);
  return result;
}

}  // namespace aperture
