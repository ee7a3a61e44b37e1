#include "core/anim/elastic_pairs.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/bind/closest_surface_point.h"
#include "core/anim/space_warp.h"
#include "core/util/error.h"

namespace dfm {

namespace {

// Farthest-point samples of X's rows, after the rows of `taken` (already chosen elsewhere): up to n,
// none nearer than `min_gap` to another or to `taken`. Deterministic: starts from the first row
// farthest from `taken`, or row 0.
std::vector<int> farthest_samples(const Eigen::MatrixXd& X, const Eigen::MatrixXd& taken, int n, double min_gap) {
  Eigen::VectorXd gap = Eigen::VectorXd::Constant(X.rows(), HUGE_VAL);
  for (Eigen::Index t = 0; t < taken.rows(); ++t)
    gap = gap.cwiseMin((X.rowwise() - taken.row(t)).rowwise().norm());
  std::vector<int> out;
  while (static_cast<int>(out.size()) < n) {
    Eigen::Index best = 0;
    const double far = gap.maxCoeff(&best);
    if (!(far >= min_gap)) break;
    out.push_back(static_cast<int>(best));
    gap = gap.cwiseMin((X.rowwise() - X.row(best)).rowwise().norm());
  }
  return out;
}

// The nearest points of `tree`'s surface to the rows of P, as the same points of `image`, a surface
// of the same triangles (by their barycentric coordinates).
Eigen::MatrixXd nearest_on(const SurfaceTree& tree, const Eigen::MatrixXd& image, const Eigen::MatrixXd& P) {
  Eigen::MatrixXd out(P.rows(), 3);
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    const SurfaceSample s = tree.closest(P.row(i).transpose());
    if (!s.found()) throw Error("elastic pairs: no surface point within reach");
    out.row(i).setZero();
    for (int k = 0; k < 3; ++k) out.row(i) += s.weight[k] * image.row(s.vertex[k]);
  }
  return out;
}

// The warp through `pairs` and the target's vertices it carries back. Throws dfm::Error when a step
// cannot be fitted or inverted.
ElasticFit carry_back(const Eigen::MatrixXd& pairs, const TriMesh& target, int steps) {
  ElasticFit f;
  f.warp = fit_warp_path(pairs.leftCols(3), pairs.rightCols(3), steps);
  f.carried = unwarp_rows(f.warp, target.V);
  return f;
}

// One round's pairs: the carried target's samples paired with their nearest source points, then the
// source's samples with their nearest carried-target points (as the same points of the target
// itself), none within `gap` of a picked point or of each other.
Eigen::MatrixXd closest_point_pairs(const TriMesh& source, const SurfaceTree& source_tree, const TriMesh& target,
                                    const Eigen::MatrixXd& carried, const Eigen::MatrixXd& picked, int samples, double gap,
                                    double reach) {
  const std::vector<int> ts = farthest_samples(carried, picked.leftCols(3), samples, gap);
  Eigen::MatrixXd from_t(ts.size(), 3), to_t(ts.size(), 3);
  for (size_t i = 0; i < ts.size(); ++i) from_t.row(i) = carried.row(ts[i]), to_t.row(i) = target.V.row(ts[i]);
  from_t = nearest_on(source_tree, source.V, from_t);
  Eigen::MatrixXd taken(picked.rows() + from_t.rows(), 3);
  taken << picked.leftCols(3), from_t;
  const std::vector<int> ss = farthest_samples(source.V, taken, samples, gap);
  Eigen::MatrixXd from_s(ss.size(), 3);
  for (size_t i = 0; i < ss.size(); ++i) from_s.row(i) = source.V.row(ss[i]);
  const Eigen::MatrixXd to_s = nearest_on(SurfaceTree(carried, target.F, reach), target.V, from_s);
  Eigen::MatrixXd out(from_t.rows() + from_s.rows(), 6);
  out << from_t, to_t, from_s, to_s;
  return out;
}

Eigen::MatrixXd stacked(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  Eigen::MatrixXd out(a.rows() + b.rows(), 6);
  out << a, b;
  return out;
}

}  // namespace

ElasticFit elastic_pairs(const TriMesh& source, const TriMesh& target, const Eigen::MatrixXd& picked,
                         const ElasticPairOptions& o) {
  if (picked.cols() != 6) throw Error("elastic pairs: picked pairs need 6 columns");
  if (o.samples < 1 || o.rounds < 0) throw Error("elastic pairs: needs at least one sample and no negative rounds");
  const double diag = (source.V.colwise().maxCoeff() - source.V.colwise().minCoeff()).norm();
  // n samples spread over a key lie about diag / sqrt(n) apart; none nearer than half that.
  const double gap = 0.5 * diag / std::sqrt(static_cast<double>(o.samples));
  const SurfaceTree source_tree(source.V, source.F, 2 * diag);
  ElasticFit kept;
  Eigen::MatrixXd carried;  // by the warp through the picked pairs and the kept ones
  for (int round = 0; round < o.rounds; ++round) {
    try {
      if (round == 0) carried = carry_back(picked, target, o.steps).carried;
      const Eigen::MatrixXd next =
          closest_point_pairs(source, source_tree, target, carried, picked, o.samples, gap, 2 * diag);
      // Kept only if the warp through them stays invertible on both keys.
      ElasticFit candidate = carry_back(stacked(picked, next), target, o.steps);
      if (first_fold(candidate.warp, source.V) || first_fold(candidate.warp, candidate.carried)) break;
      candidate.pairs = next;
      carried = candidate.carried;
      kept = std::move(candidate);
    } catch (const Error&) {
      break;
    }
  }
  return kept;
}

}  // namespace dfm
