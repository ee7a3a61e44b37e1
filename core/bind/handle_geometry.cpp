#include "core/bind/handle_geometry.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>

#include "core/util/error.h"

namespace dfm {

double mean_edge_length(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  double sum = 0;
  long n = 0;
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      sum += (V.row(F(f, k)) - V.row(F(f, (k + 1) % 3))).norm();
      ++n;
    }
  return n ? sum / n : 0.0;
}

std::vector<HandleSample> sample_handles(const Rig& rig, double spacing) {
  std::vector<HandleSample> out;
  for (int i = 0; i < num_point_handles(rig); ++i) {
    const int h = handle_index(rig, {HandleKind::Point, i});
    out.push_back({rig.points[i].position, {{h, 1.0}}, h, true});
  }
  const Skeleton& s = rig.skeleton;
  for (int i = 0; i < s.num_bones(); ++i) {
    const Bone& bone = s.bones[i];
    const int h = handle_index(rig, {HandleKind::Bone, i});
    if (bone.a < 0 || bone.b < 0 || bone.a >= s.num_joints() || bone.b >= s.num_joints())
      throw Error("bone " + handle_name(rig, h) + " refers to a missing joint");
    const Eigen::Vector3d a = s.joints.row(bone.a).transpose(), b = s.joints.row(bone.b).transpose();
    const double len = (b - a).norm();
    const int n = spacing > 0 ? std::max(1, static_cast<int>(std::ceil(len / spacing))) : 1;
    for (int k = 0; k <= n; ++k) {
      // Joints exactly (not a + 1 * (b - a)) so that bones sharing a joint share its sample.
      const Eigen::Vector3d x = k == 0 ? a : k == n ? b : Eigen::Vector3d(a + (b - a) * (double(k) / n));
      out.push_back({x, {{h, 1.0}}, h, false});
    }
  }
  CageSoup cages = stack_cages(rig);
  for (int i = 0; i < cages.V.rows(); ++i)
    out.push_back({cages.V.row(i).transpose(), {{cages.handle[i], 1.0}}, cages.handle[i], true});
  return out;
}

CageSoup stack_cages(const Rig& rig) {
  CageSoup s;
  const int nv = num_cage_vertices(rig);
  int nf = 0, ne = 0;
  for (const Cage& c : rig.cages) nf += c.mesh.num_faces(), ne += static_cast<int>(c.edges.rows());
  s.V.resize(nv, 3);
  s.F.resize(nf, 3);
  s.E.resize(ne, 2);
  int ov = 0, of = 0, oe = 0;
  for (int c = 0; c < static_cast<int>(rig.cages.size()); ++c) {
    const Cage& cage = rig.cages[c];
    const int n = cage.mesh.num_vertices();
    auto check = [&](int v) {
      if (v < 0 || v >= n)
        throw Error((cage.name.empty() ? "cage " + std::to_string(c) : cage.name) + ": vertex index " +
                    std::to_string(v) + " out of range");
    };
    if (n) s.V.middleRows(ov, n) = cage.mesh.V;
    for (int i = 0; i < n; ++i) s.handle.push_back(handle_index(rig, {HandleKind::CageVertex, i, c}));
    for (int f = 0; f < cage.mesh.num_faces(); ++f, ++of) {
      for (int k = 0; k < 3; ++k) check(cage.mesh.F(f, k)), s.F(of, k) = ov + cage.mesh.F(f, k);
      s.cage.push_back(c);
    }
    if (cage.edges.rows() && cage.edges.cols() != 2) throw Error("cage edges must have two columns");
    for (int e = 0; e < cage.edges.rows(); ++e, ++oe)
      for (int k = 0; k < 2; ++k) check(cage.edges(e, k)), s.E(oe, k) = ov + cage.edges(e, k);
    ov += n;
  }
  return s;
}

bool is_closed_surface(const Eigen::MatrixXi& F) {
  if (F.rows() == 0) return false;
  std::map<std::pair<int, int>, int> count;
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      int a = F(f, k), b = F(f, (k + 1) % 3);
      ++count[{std::min(a, b), std::max(a, b)}];
    }
  for (const auto& [e, n] : count)
    if (n != 2) return false;
  return true;
}

void BoundaryRows::add(int v, const std::vector<std::pair<int, double>>& w) {
  if (v >= static_cast<int>(index_.size())) index_.resize(v + 1, -1);
  if (index_[v] < 0) {
    index_[v] = static_cast<int>(rows_.size());
    rows_.push_back({v, {}});
  }
  auto& r = rows_[index_[v]].second;
  r.insert(r.end(), w.begin(), w.end());
}

bool BoundaryRows::has(int v) const { return v >= 0 && v < static_cast<int>(index_.size()) && index_[v] >= 0; }

void BoundaryRows::finish(int num_handles, Eigen::VectorXi& b, Eigen::MatrixXd& bc) const {
  std::vector<int> order(rows_.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::sort(order.begin(), order.end(), [&](int x, int y) { return rows_[x].first < rows_[y].first; });
  b.resize(order.size());
  bc = Eigen::MatrixXd::Zero(order.size(), num_handles);
  for (size_t i = 0; i < order.size(); ++i) {
    const auto& [v, w] = rows_[order[i]];
    b(i) = v;
    for (const auto& [h, x] : w) bc(i, h) += x;
    const double s = bc.row(i).sum();
    if (s > 0) bc.row(i) /= s;
  }
}

void add_cage_surface_rows(const Eigen::MatrixXd& TV, const CageSoup& cages, double tol, BoundaryRows& rows) {
  if (cages.F.rows() == 0 && cages.E.rows() == 0) return;
  for (int v = 0; v < TV.rows(); ++v) {
    if (rows.has(v)) continue;
    const Eigen::Vector3d p = TV.row(v).transpose();
    bool done = false;
    for (int f = 0; f < cages.F.rows() && !done; ++f) {
      const Eigen::Vector3d a = cages.V.row(cages.F(f, 0)), b = cages.V.row(cages.F(f, 1)), c = cages.V.row(cages.F(f, 2));
      if ((p.array() < a.cwiseMin(b).cwiseMin(c).array() - tol).any() ||
          (p.array() > a.cwiseMax(b).cwiseMax(c).array() + tol).any())
        continue;
      const Eigen::Vector3d n = (b - a).cross(c - a);
      const double area2 = n.norm();
      if (area2 <= 0 || std::abs((p - a).dot(n)) / area2 > tol) continue;
      // Barycentric coordinates from sub-triangle areas (signed along n).
      const double la = (b - p).cross(c - p).dot(n) / (area2 * area2);
      const double lb = (c - p).cross(a - p).dot(n) / (area2 * area2);
      const double lc = 1.0 - la - lb;
      const double slack = tol / std::sqrt(area2);
      if (la < -slack || lb < -slack || lc < -slack) continue;
      Eigen::Vector3d l(std::max(0.0, la), std::max(0.0, lb), std::max(0.0, lc));
      l /= l.sum();
      std::vector<std::pair<int, double>> w;
      for (int k = 0; k < 3; ++k)
        if (l(k) > 0) w.push_back({cages.handle[cages.F(f, k)], l(k)});
      rows.add(v, w);
      done = true;
    }
    for (int e = 0; e < cages.E.rows() && !done; ++e) {
      const Eigen::Vector3d a = cages.V.row(cages.E(e, 0)), b = cages.V.row(cages.E(e, 1));
      const Eigen::Vector3d d = b - a;
      const double l2 = d.squaredNorm();
      if (l2 <= 0) continue;
      const double t = std::clamp((p - a).dot(d) / l2, 0.0, 1.0);
      if ((a + t * d - p).norm() > tol) continue;
      std::vector<std::pair<int, double>> w;
      if (t < 1) w.push_back({cages.handle[cages.E(e, 0)], 1 - t});
      if (t > 0) w.push_back({cages.handle[cages.E(e, 1)], t});
      rows.add(v, w);
      done = true;
    }
  }
}

std::array<long long, 3> PointWelder::cell(const Eigen::Vector3d& x) const {
  std::array<long long, 3> c;
  for (int k = 0; k < 3; ++k) c[k] = static_cast<long long>(std::floor(x(k) / tol_));
  return c;
}

long long PointWelder::hash(const std::array<long long, 3>& c) {
  return c[0] * 73856093LL ^ c[1] * 19349663LL ^ c[2] * 83492791LL;
}

int PointWelder::find(const Eigen::Vector3d& x) const {
  const auto c = cell(x);
  int best = -1;
  double bd = tol_;
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j)
      for (int k = -1; k <= 1; ++k) {
        auto range = grid_.equal_range(hash({c[0] + i, c[1] + j, c[2] + k}));
        for (auto it = range.first; it != range.second; ++it) {
          const double d = (pts_[it->second] - x).norm();
          if (d <= bd) bd = d, best = it->second;
        }
      }
  return best;
}

int PointWelder::add(const Eigen::Vector3d& x) {
  if (!x.allFinite()) throw Error("handle position is not finite");
  const int f = find(x);
  if (f >= 0) return f;
  return insert(x);
}

int PointWelder::insert(const Eigen::Vector3d& x) {
  pts_.push_back(x);
  grid_.emplace(hash(cell(x)), static_cast<int>(pts_.size()) - 1);
  return static_cast<int>(pts_.size()) - 1;
}

Eigen::MatrixXd PointWelder::matrix() const {
  Eigen::MatrixXd M(pts_.size(), 3);
  for (size_t i = 0; i < pts_.size(); ++i) M.row(i) = pts_[i].transpose();
  return M;
}

}  // namespace dfm
