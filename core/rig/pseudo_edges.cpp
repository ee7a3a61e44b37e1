#include "core/rig/pseudo_edges.h"

#include <string>

#include "core/util/error.h"

namespace dfm {

Eigen::Quaterniond average_quaternions(const std::vector<Eigen::Quaterniond>& qs) {
  if (qs.empty()) return Eigen::Quaterniond::Identity();
  Eigen::Vector4d sum = Eigen::Vector4d::Zero();
  const Eigen::Vector4d first = qs.front().coeffs();
  for (const auto& q : qs) sum += (q.coeffs().dot(first) < 0 ? -1.0 : 1.0) * q.coeffs();
  if (sum.norm() == 0) return qs.front().normalized();
  Eigen::Quaterniond r;
  r.coeffs() = sum.normalized();
  return r;
}

std::vector<Eigen::Quaterniond> pseudo_edge_rotations(const Eigen::MatrixXd& rest, const Eigen::MatrixXd& posed,
                                                      const std::vector<std::pair<int, int>>& edges,
                                                      std::vector<bool>* has_edge) {
  const int n = static_cast<int>(rest.rows());
  if (posed.rows() != n) throw Error("pseudo-edges: rest and posed point counts differ");
  std::vector<std::vector<Eigen::Quaterniond>> per(n);
  for (const auto& [i, j] : edges) {
    if (i < 0 || j < 0 || i >= n || j >= n || i == j)
      throw Error("pseudo-edge (" + std::to_string(i) + ", " + std::to_string(j) + ") is not between two of the " +
                  std::to_string(n) + " point handles");
    const Eigen::Vector3d d0 = (rest.row(j) - rest.row(i)).transpose();
    const Eigen::Vector3d d1 = (posed.row(j) - posed.row(i)).transpose();
    if (d0.norm() == 0 || d1.norm() == 0) continue;
    // The rotation taking i->j's direction is the same one taking j->i's: both ends get it.
    const Eigen::Quaterniond q = Eigen::Quaterniond::FromTwoVectors(d0, d1);
    per[i].push_back(q);
    per[j].push_back(q);
  }
  std::vector<Eigen::Quaterniond> out(n);
  if (has_edge) has_edge->assign(n, false);
  for (int i = 0; i < n; ++i) {
    out[i] = average_quaternions(per[i]);
    if (has_edge) (*has_edge)[i] = !per[i].empty();
  }
  return out;
}

}  // namespace dfm
