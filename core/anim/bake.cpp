#include "core/anim/bake.h"

#include <string>

#include "core/anim/interpolate.h"
#include "core/util/error.h"

namespace dfm {

std::vector<double> bake_times(const KeyTrack& track, int inbetweens) {
  if (track.empty()) throw Error("cannot bake an empty key track");
  if (inbetweens < 0) throw Error("in-betweens per interval must be >= 0, got " + std::to_string(inbetweens));
  const auto& keys = track.keys();
  std::vector<double> times;
  for (size_t i = 0; i < keys.size(); ++i) {
    times.push_back(keys[i].time);
    if (i + 1 == keys.size()) break;
    const double t0 = keys[i].time, t1 = keys[i + 1].time;
    for (int j = 1; j <= inbetweens; ++j) times.push_back(t0 + (t1 - t0) * j / (inbetweens + 1));
  }
  return times;
}

BakedLayers bake_layers(const KeyTrack& track, int inbetweens, const SkinFunction& skin,
                        const BakeProgress& progress) {
  return bake_layers(bake_times(track, inbetweens), [&](double t) { return sample_track(track, t); }, skin, progress);
}

BakedLayers bake_layers(const std::vector<double>& times, const std::function<Pose(double)>& pose_at,
                        const SkinFunction& skin, const BakeProgress& progress) {
  return bake_layers(times, [&](double t) { return skin(pose_at(t)); }, progress);
}

BakedLayers bake_layers(const std::vector<double>& times, const std::function<Eigen::MatrixXd(double)>& positions_at,
                        const BakeProgress& progress) {
  BakedLayers out;
  out.times = times;
  const int total = static_cast<int>(out.times.size());
  out.positions.reserve(total);
  for (int i = 0; i < total; ++i) {
    Eigen::MatrixXd P = positions_at(out.times[i]);
    if (P.cols() != 3 || (i > 0 && P.rows() != out.positions[0].rows()))
      throw Error("bake: skinning at time " + std::to_string(out.times[i]) + " gave " +
                  std::to_string(P.rows()) + " x " + std::to_string(P.cols()) + " positions, expected " +
                  (i > 0 ? std::to_string(out.positions[0].rows()) : std::string("#V")) + " x 3");
    out.positions.push_back(std::move(P));
    if (progress && !progress(i + 1, total)) throw Cancelled("bake cancelled");
  }
  return out;
}

}  // namespace dfm
