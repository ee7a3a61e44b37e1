#include "core/anim/manifold_edit_volume.h"

#include <cmath>
#include <map>

#include "core/anim/surface_checks.h"
#include "core/util/error.h"

namespace dfm {

double layer_volume(const MatrixX4dRow& V, const Eigen::MatrixXi& F) {
  double v = 0;
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)).head<3>(), b = V.row(F(f, 1)).head<3>(), c = V.row(F(f, 2)).head<3>();
    v += a.dot(b.cross(c));
  }
  return v / 6;
}

std::vector<EditLayer> edit_layers(const AnimationManifold& m, const std::vector<int>& movable,
                                   const std::vector<double>& weight) {
  // Layer first vertex -> (vertex count, triangle list).
  std::map<int, std::pair<int, int>> layers;
  for (const PrismSlab& s : m.prism_slabs) {
    if (!s.is_prism()) continue;
    layers[s.lower] = {s.count, s.faces};
    layers[s.upper] = {s.count, s.faces};
  }
  std::map<int, EditLayer> used;
  for (size_t i = 0; i < movable.size(); ++i) {
    const int v = movable[i];
    auto it = layers.upper_bound(v);
    if (it == layers.begin() || v >= std::prev(it)->first + std::prev(it)->second.first)
      throw Error("volume preservation: vertex " + std::to_string(v) +
                  " is on no time layer (it needs a manifold built from keyframes of one connectivity)");
    --it;
    EditLayer& L = used[it->first];
    if (L.F.size() == 0) {
      const Eigen::MatrixXi& F = m.layer_faces.at(it->second.second);
      if (!is_closed_and_oriented(F))
        throw Error("volume preservation: the layer at t = " + std::to_string(m.V(it->first, 3)) + " is not a closed surface");
      L.F = F.array() + it->first;
      L.volume = layer_volume(m.V, L.F);
    }
    L.movable.push_back(v);
    L.weight.push_back(weight[i]);
  }
  std::vector<EditLayer> out;
  for (auto& [first, L] : used) out.push_back(std::move(L));
  return out;
}

void restore_layer_volumes(const std::vector<EditLayer>& layers, MatrixX4dRow& V) {
  for (const EditLayer& L : layers) {
    // Gradient of the volume per vertex: (1/6) sum over its triangles (a, b, c) of b x c.
    std::map<int, Eigen::Vector3d> grad;
    for (int v : L.movable) grad[v] = Eigen::Vector3d::Zero();
    for (int f = 0; f < L.F.rows(); ++f)
      for (int j = 0; j < 3; ++j) {
        const auto it = grad.find(L.F(f, j));
        if (it == grad.end()) continue;
        const Eigen::Vector3d b = V.row(L.F(f, (j + 1) % 3)).head<3>(), c = V.row(L.F(f, (j + 2) % 3)).head<3>();
        it->second += b.cross(c) / 6;
      }
    Eigen::MatrixXd dir(L.movable.size(), 3);
    for (size_t i = 0; i < L.movable.size(); ++i) dir.row(i) = L.weight[i] * grad[L.movable[i]].transpose();
    double slope = 0;
    for (size_t i = 0; i < L.movable.size(); ++i) slope += dir.row(i).dot(grad[L.movable[i]].transpose());
    if (!(slope > 0)) continue;
    for (int step = 0; step < 4; ++step) {
      const double gap = L.volume - layer_volume(V, L.F);
      if (std::abs(gap) <= 1e-12 * std::abs(L.volume)) break;
      const double h = gap / slope;
      for (size_t i = 0; i < L.movable.size(); ++i) V.row(L.movable[i]).head<3>() += h * dir.row(i);
    }
  }
}

}  // namespace dfm
