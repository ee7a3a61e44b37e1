#include "core/anim/lattice_refinement.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_set>

#include "core/bind/parallel_for.h"
#include "core/util/error.h"

namespace dfm {

namespace {

// The largest distance, in units of the field, by which the cubic p with p(0) = fa, p(1) = fb,
// p'(0) = da, p'(1) = db (derivatives per the whole edge) moves the zero set off the chord, at
// s = 1/4, 1/2, 3/4: |p(s) - chord(s)| where the zero set lies between them (one of them is within
// that of 0), else 0. p(s) - chord(s) = s (1 - s) [(da - D) (1 - s) + (D - db) s], D = fb - fa.
double zero_set_bulge(double fa, double fb, double da, double db) {
  const double D = fb - fa;
  double m = 0;
  for (double s : {0.25, 0.5, 0.75}) {
    const double chord = fa + s * D, off = s * (1 - s) * ((da - D) * (1 - s) + (D - db) * s), p = chord + off;
    if ((p < 0) != (chord < 0) || std::min(std::abs(p), std::abs(chord)) <= std::abs(off)) m = std::max(m, std::abs(off));
  }
  return m;
}

}  // namespace

Eigen::MatrixXd bulging_edge_midpoints(const Eigen::MatrixXd& X, const std::vector<std::array<int, 2>>& edges,
                                       const Eigen::VectorXd& d_s, const Eigen::VectorXd& d_t, const Eigen::MatrixXd& g_s,
                                       const Eigen::MatrixXd& g_t, const std::vector<double>& u, double a,
                                       double tolerance) {
  const Eigen::Index n = X.rows();
  if (X.cols() != 3 || d_s.size() != n || d_t.size() != n || g_s.rows() != n || g_t.rows() != n || g_s.cols() != 3 ||
      g_t.cols() != 3)
    throw Error("bulging_edge_midpoints: points, values and gradients disagree in size");
  for (const std::array<int, 2>& e : edges)
    if (std::min(e[0], e[1]) < 0 || std::max(e[0], e[1]) >= n) throw Error("bulging_edge_midpoints: an edge's point index is out of range");
  std::vector<char> flagged(edges.size(), 0);
  parallel_for(static_cast<int>(edges.size()), 0, [&](int k) {
    const int i = edges[k][0], j = edges[k][1];
    const Eigen::RowVector3d e = X.row(j) - X.row(i);
    for (double w : u) {
      const double fi = (1 - w) * d_s[i] + w * d_t[i], fj = (1 - w) * d_s[j] + w * d_t[j];
      const Eigen::RowVector3d gi = (1 - w) * g_s.row(i) + w * g_t.row(i), gj = (1 - w) * g_s.row(j) + w * g_t.row(j);
      const double slope = 0.5 * (gi.norm() + gj.norm());
      if (!(slope > 0)) continue;
      if (zero_set_bulge(fi, fj, gi.dot(e), gj.dot(e)) > tolerance * a * slope) {
        flagged[k] = 1;
        return;
      }
    }
  });
  std::vector<Eigen::RowVector3d> mid;
  for (size_t k = 0; k < edges.size(); ++k)
    if (flagged[k]) mid.push_back(0.5 * (X.row(edges[k][0]) + X.row(edges[k][1])));
  Eigen::MatrixXd M(static_cast<Eigen::Index>(mid.size()), 3);
  for (size_t k = 0; k < mid.size(); ++k) M.row(static_cast<Eigen::Index>(k)) = mid[k];
  return M;
}

Eigen::MatrixXd finer_lattice_points(const Eigen::RowVector3d& lo, double a, const Eigen::MatrixXd& centres,
                                     double reach) {
  const double q = 0.25 * a;
  struct Hash {
    size_t operator()(const std::array<long long, 3>& c) const {
      return static_cast<size_t>(static_cast<unsigned long long>(c[0]) * 0x9E3779B97F4A7C15ull ^
                                 static_cast<unsigned long long>(c[1]) * 0xC2B2AE3D27D4EB4Full ^
                                 static_cast<unsigned long long>(c[2]) * 0x165667B19E3779F9ull);
    }
  };
  std::unordered_set<std::array<long long, 3>, Hash> seen;
  std::vector<Eigen::RowVector3d> out;
  const long long r = static_cast<long long>(std::ceil(reach / q));
  for (Eigen::Index c = 0; c < centres.rows(); ++c) {
    const Eigen::RowVector3d p = (centres.row(c) - lo) / q;
    const long long cx = std::llround(p[0]), cy = std::llround(p[1]), cz = std::llround(p[2]);
    for (long long x = cx - r; x <= cx + r; ++x)
      for (long long y = cy - r; y <= cy + r; ++y)
        for (long long z = cz - r; z <= cz + r; ++z) {
          const int odd = static_cast<int>((x & 1) + (y & 1) + (z & 1));
          if (odd != 0 && odd != 3) continue;
          const long long mx = x & 3, my = y & 3, mz = z & 3;
          if (mx == my && my == mz && (mx == 0 || mx == 2)) continue;  // a coarse lattice point
          const Eigen::RowVector3d point = lo + Eigen::RowVector3d(static_cast<double>(x), static_cast<double>(y), static_cast<double>(z)) * q;
          if ((point - centres.row(c)).squaredNorm() > reach * reach) continue;
          if (seen.insert({x, y, z}).second) out.push_back(point);
        }
  }
  Eigen::MatrixXd P(static_cast<Eigen::Index>(out.size()), 3);
  for (size_t i = 0; i < out.size(); ++i) P.row(static_cast<Eigen::Index>(i)) = out[i];
  return P;
}

}  // namespace dfm
