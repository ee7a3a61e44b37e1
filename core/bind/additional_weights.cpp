#include "core/bind/additional_weights.h"

#include <algorithm>
#include <limits>
#include <string>

#include "core/util/error.h"

namespace dfm {

std::vector<int> farthest_point_samples(const Eigen::MatrixXd& V, const std::vector<int>& seeds, int k) {
  if (seeds.empty()) throw Error("additional weights: no constrained vertices to sample away from");
  Eigen::VectorXd d = Eigen::VectorXd::Constant(V.rows(), std::numeric_limits<double>::infinity());
  auto take = [&](int s) { d = d.cwiseMin((V.rowwise() - V.row(s)).rowwise().norm()); };
  for (int s : seeds) take(s);
  std::vector<int> out;
  for (int i = 0; i < k; ++i) {
    Eigen::Index best;
    if (!(d.maxCoeff(&best) > 0))
      throw Error("additional weights: only " + std::to_string(i) + " vertices away from the handles, " +
                  std::to_string(k) + " asked");
    out.push_back(static_cast<int>(best));
    take(static_cast<int>(best));
  }
  return out;
}

AdditionalWeights additional_weights(const BindResult& bind, int k, const BindOptions& opts) {
  if (k < 1) throw Error("additional weights: k must be >= 1, got " + std::to_string(k));
  const BindVolume& vol = bind.volume;
  const std::vector<int> seeds(vol.b.data(), vol.b.data() + vol.b.size());
  const std::vector<int> samples = farthest_point_samples(vol.tets.V, seeds, k);
  // The same volume and constraints, each sample one more handle: 1 at its vertex, 0 at the others'.
  BindVolume more = vol;
  const int m = static_cast<int>(vol.bc.cols()), nb = static_cast<int>(vol.b.size());
  more.b.conservativeResize(nb + k);
  more.bc = Eigen::MatrixXd::Zero(nb + k, m + k);
  more.bc.topLeftCorner(nb, m) = vol.bc;
  for (int i = 0; i < k; ++i) {
    more.b(nb + i) = samples[i];
    more.bc(nb + i, m + i) = 1;
  }
  BindOptions o = opts;
  o.endpoint_weights = false;
  BindResult r = bind_on_volume(std::move(more), o);
  AdditionalWeights out;
  out.weights = r.weights.rightCols(k);
  for (int s : samples) out.points.push_back(vol.tets.V.row(s).transpose());
  out.report = r.report;
  return out;
}

}  // namespace dfm
