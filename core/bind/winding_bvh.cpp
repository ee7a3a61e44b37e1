#include "core/bind/winding_bvh.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/bind/parallel_for.h"
#include "core/bind/winding_number.h"

namespace dfm {
namespace {

void fill_moments(WindingTree& t, WindingTree::Node& n) {
  double area = 0;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  n.N.setZero();
  for (int i = n.begin; i < n.end; ++i) {
    Eigen::Vector3d av = 0.5 * (t.b[i] - t.a[i]).cross(t.c[i] - t.a[i]);
    double ar = av.norm();
    n.N += av;
    area += ar;
    c += ar * (t.a[i] + t.b[i] + t.c[i]) / 3.0;
  }
  if (area > 0) {
    c /= area;
  } else {  // all degenerate: any point will do
    c = t.a[n.begin];
  }
  n.center = c;
  n.area = area;
  n.M.setZero();
  for (auto& h : n.H) h.setZero();
  n.radius = 0;
  for (int i = n.begin; i < n.end; ++i) {
    Eigen::Vector3d av = 0.5 * (t.b[i] - t.a[i]).cross(t.c[i] - t.a[i]);
    Eigen::Vector3d da = t.a[i] - c, db = t.b[i] - c, dc = t.c[i] - c;
    Eigen::Vector3d s = da + db + dc;
    n.M += av * (s / 3.0).transpose();
    // int_T d d^T dA = area/12 (sum_v d_v d_v^T + s s^T); the area is folded into av.
    Eigen::Matrix3d S = (da * da.transpose() + db * db.transpose() + dc * dc.transpose() + s * s.transpose()) / 12.0;
    for (int k = 0; k < 3; ++k) n.H[k] += av(k) * S;
    n.radius = std::max({n.radius, da.norm(), db.norm(), dc.norm()});
  }
}

}  // namespace

WindingTree build_winding_tree(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, int leaf_size) {
  WindingTree t;
  t.leaf_size = std::max(1, leaf_size);
  const int nf = static_cast<int>(F.rows());
  std::vector<int> order(nf);
  std::iota(order.begin(), order.end(), 0);
  std::vector<Eigen::Vector3d> cen(nf);
  for (int f = 0; f < nf; ++f)
    cen[f] = (V.row(F(f, 0)) + V.row(F(f, 1)) + V.row(F(f, 2))).transpose() / 3.0;
  if (nf == 0) return t;
  // Median split on the longest axis of the centroids' box, built breadth-first into one array.
  t.nodes.reserve(2 * nf / t.leaf_size + 2);
  t.nodes.push_back({});
  t.nodes[0].begin = 0;
  t.nodes[0].end = nf;
  for (size_t k = 0; k < t.nodes.size(); ++k) {
    const int b = t.nodes[k].begin, e = t.nodes[k].end;
    if (e - b <= t.leaf_size) continue;
    Eigen::Vector3d lo = cen[order[b]], hi = lo;
    for (int i = b; i < e; ++i) {
      lo = lo.cwiseMin(cen[order[i]]);
      hi = hi.cwiseMax(cen[order[i]]);
    }
    int axis;
    (hi - lo).maxCoeff(&axis);
    const int mid = (b + e) / 2;
    std::nth_element(order.begin() + b, order.begin() + mid, order.begin() + e,
                     [&](int x, int y) { return cen[x](axis) < cen[y](axis); });
    WindingTree::Node l, r;
    l.begin = b, l.end = mid, r.begin = mid, r.end = e;
    t.nodes[k].left = static_cast<int>(t.nodes.size());
    t.nodes[k].right = t.nodes[k].left + 1;
    t.nodes.push_back(l);
    t.nodes.push_back(r);
  }
  t.a.resize(nf), t.b.resize(nf), t.c.resize(nf);
  for (int i = 0; i < nf; ++i) {
    t.a[i] = V.row(F(order[i], 0)).transpose();
    t.b[i] = V.row(F(order[i], 1)).transpose();
    t.c[i] = V.row(F(order[i], 2)).transpose();
  }
  for (auto& n : t.nodes) fill_moments(t, n);
  return t;
}

double winding_number(const WindingTree& t, const Eigen::Vector3d& p, const WindingAccuracy& acc) {
  const double beta2 = acc.beta * acc.beta, tol = 4.0 * M_PI * acc.node_tolerance;
  if (t.nodes.empty()) return 0;
  double sum = 0;  // in units of 4 pi
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const WindingTree::Node& n = t.nodes[stack[--top]];
    const Eigen::Vector3d R = n.center - p;
    const double r2 = R.squaredNorm();
    const double rad3 = n.radius * n.radius * n.radius;
    if (r2 > beta2 * n.radius * n.radius && n.area * rad3 < tol * r2 * r2 * std::sqrt(r2)) {
      // Far field: Taylor expansion of K(r) = r / |r|^3 about the node center.
      const double r = std::sqrt(r2), ir2 = 1.0 / r2, ir3 = ir2 / r, ir5 = ir3 * ir2, ir7 = ir5 * ir2;
      double w = R.dot(n.N) * ir3;
      w += n.M.trace() * ir3 - 3.0 * R.dot(n.M * R) * ir5;
      double hr = 0, rtr = 0, rhr = 0;
      for (int i = 0; i < 3; ++i) {
        const Eigen::Vector3d HR = n.H[i] * R;
        hr += HR(i);
        rtr += R(i) * n.H[i].trace();
        rhr += R(i) * R.dot(HR);
      }
      w += 0.5 * (-3.0 * (2.0 * hr + rtr) * ir5 + 15.0 * rhr * ir7);
      sum += w;
    } else if (n.left < 0) {
      for (int i = n.begin; i < n.end; ++i) sum += solid_angle(t.a[i], t.b[i], t.c[i], p);
    } else {
      stack[top++] = n.left;
      stack[top++] = n.right;
    }
  }
  return sum / (4.0 * M_PI);
}

Eigen::VectorXd winding_numbers(const WindingTree& tree, const Eigen::MatrixXd& P, const WindingAccuracy& acc,
                                int threads) {
  Eigen::VectorXd w(P.rows());
  parallel_for(static_cast<int>(P.rows()), threads, [&](int i) { w(i) = winding_number(tree, P.row(i).transpose(), acc); });
  return w;
}

}  // namespace dfm
