#pragma once
// Baking: the posed mesh sampled at every key and at `inbetweens` evenly spaced times inside each
// key interval. These meshes (same connectivity) become the animation manifold's time layers.
// Skinning is passed in as a callable so this module does not fix a skinning method.
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "core/anim/keyframes.h"

namespace dfm {

// Pose -> #V x 3 posed vertex positions (e.g. LBS of the rest mesh with bound weights).
using SkinFunction = std::function<Eigen::MatrixXd(const Pose&)>;
// Called after each layer with (done, total); return false to cancel (bake then throws dfm::Cancelled).
using BakeProgress = std::function<bool(int done, int total)>;

struct BakedLayers {
  std::vector<double> times;                // strictly increasing
  std::vector<Eigen::MatrixXd> positions;   // one #V x 3 matrix per time
};

// The layer times: every key, plus `inbetweens` evenly spaced times strictly inside each interval.
std::vector<double> bake_times(const KeyTrack& track, int inbetweens);

// positions_at(t) at each of `times` (strictly increasing). Throws dfm::Error on a result whose size
// changes between layers, or cancellation.
BakedLayers bake_layers(const std::vector<double>& times, const std::function<Eigen::MatrixXd(double)>& positions_at,
                        const BakeProgress& progress = {});
// Skins pose_at(t) at each of `times`, as above.
BakedLayers bake_layers(const std::vector<double>& times, const std::function<Pose(double)>& pose_at,
                        const SkinFunction& skin, const BakeProgress& progress = {});

// Samples the track (rotation-aware, see interpolate.h) at bake_times and skins each pose.
// Throws dfm::Error on an empty track, inbetweens < 0, a skin result whose size changes between
// layers, or cancellation.
BakedLayers bake_layers(const KeyTrack& track, int inbetweens, const SkinFunction& skin,
                        const BakeProgress& progress = {});

}  // namespace dfm
