#include "core/scene/weight_brush.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/bind/surface_laplacian.h"
#include "core/scene/brush.h"
#include "core/skin/skin.h"
#include "core/util/error.h"

namespace dfm {

WeightPaintSurface weight_paint_surface(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  WeightPaintSurface s;
  s.V = V;
  s.N = vertex_normals(V, F);
  s.K = uniform_stiffness(static_cast<int>(V.rows()), F);
  return s;
}

namespace {

void check(const Eigen::MatrixXd& W, const WeightPaintSurface& s, int handle, const WeightBrush& b,
           const std::vector<bool>& locked, const std::vector<bool>& fixed) {
  if (!(b.radius > 0)) throw Error("weight brush: radius must be > 0");
  if (!(b.strength >= 0 && b.strength <= 1)) throw Error("weight brush: strength must be in [0, 1]");
  if (!(b.falloff >= 0 && b.falloff <= 1)) throw Error("weight brush: falloff must be in [0, 1]");
  if (!(b.value >= 0 && b.value <= 1)) throw Error("weight brush: the mix value must be in [0, 1]");
  if (!b.facing.allFinite()) throw Error("weight brush: the view direction is not finite");
  if (W.rows() != s.V.rows() || s.K.rows() != s.V.rows() || s.N.rows() != s.V.rows())
    throw Error("weight brush: weights for " + std::to_string(W.rows()) + " vertices on a surface of " +
                std::to_string(s.V.rows()));
  if (handle < 0 || handle >= W.cols()) throw Error("weight brush: no handle " + std::to_string(handle));
  if (!locked.empty() && static_cast<Eigen::Index>(locked.size()) != W.cols())
    throw Error("weight brush: lock flags for " + std::to_string(locked.size()) + " handles, weights have " +
                std::to_string(W.cols()));
  if (!locked.empty() && locked[handle]) throw Error("weight brush: handle " + std::to_string(handle) + " is locked");
  if (!fixed.empty() && static_cast<Eigen::Index>(fixed.size()) != W.rows())
    throw Error("weight brush: fixed flags for " + std::to_string(fixed.size()) + " vertices");
}

// The painted weight's new value before the row is renormalized.
double painted(const Eigen::MatrixXd& W, const WeightPaintSurface& s, int v, int h, double f, const WeightBrush& b) {
  const double w = W(v, h), k = b.strength * f;
  switch (b.mode) {
    case WeightPaintMode::Add: return w + k;
    case WeightPaintMode::Subtract: return w - k;
    case WeightPaintMode::Mix: return w + k * (b.value - w);
    case WeightPaintMode::Smooth: {
      double sum = 0, degree = 0;
      for (Eigen::SparseMatrix<double>::InnerIterator it(s.K, v); it; ++it)
        if (it.row() != v) sum += W(it.row(), h), degree += 1;
      return degree > 0 ? w + k * (sum / degree - w) : w;
    }
  }
  return w;
}

// The row with weight h set to x (clamped) and the other unlocked weights scaled to fill the rest.
Eigen::RowVectorXd renormalized(Eigen::RowVectorXd row, int h, double x, const std::vector<bool>& locked) {
  double L = 0, U = 0;
  for (Eigen::Index j = 0; j < row.size(); ++j) {
    if (j == h) continue;
    if (!locked.empty() && locked[j]) L += row[j];
    else U += std::max(0.0, row[j]);
  }
  x = std::clamp(x, 0.0, std::max(0.0, 1.0 - L));
  if (U <= 0) x = std::max(0.0, 1.0 - L);  // nothing else takes the rest
  const double scale = U > 0 ? (1.0 - L - x) / U : 0.0;
  for (Eigen::Index j = 0; j < row.size(); ++j)
    if (j != h && (locked.empty() || !locked[j])) row[j] = std::max(0.0, row[j]) * scale;
  row[h] = x;
  return row;
}

}  // namespace

WeightDab weight_dab(const Eigen::MatrixXd& W, const WeightPaintSurface& s, int handle, const Eigen::Vector3d& center,
                     const WeightBrush& b, const std::vector<bool>& locked, const std::vector<bool>& fixed) {
  check(W, s, handle, b, locked, fixed);
  const bool front_only = b.facing.squaredNorm() > 0;
  const double r2 = b.radius * b.radius;
  WeightDab dab;
  std::vector<Eigen::RowVectorXd> rows;
  for (Eigen::Index v = 0; v < s.V.rows(); ++v) {
    const double d2 = (s.V.row(v).transpose() - center).squaredNorm();
    if (d2 > r2 || (!fixed.empty() && fixed[v])) continue;
    if (front_only && s.N.row(v).dot(b.facing) >= 0) continue;
    const double f = brush_weight(std::sqrt(d2), b.radius, b.falloff);
    if (f <= 0) continue;
    Eigen::RowVectorXd row = renormalized(W.row(v), handle, painted(W, s, static_cast<int>(v), handle, f, b), locked);
    if (row == W.row(v)) continue;
    dab.rows.push_back(static_cast<int>(v));
    rows.push_back(std::move(row));
  }
  dab.values.resize(static_cast<Eigen::Index>(rows.size()), W.cols());
  for (size_t i = 0; i < rows.size(); ++i) dab.values.row(static_cast<Eigen::Index>(i)) = rows[i];
  return dab;
}

void apply_weight_dab(Eigen::MatrixXd& W, const WeightDab& dab) {
  for (size_t i = 0; i < dab.rows.size(); ++i) W.row(dab.rows[i]) = dab.values.row(static_cast<Eigen::Index>(i));
}

}  // namespace dfm
