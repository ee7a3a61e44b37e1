#include "core/anim/face_protection.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include <Eigen/Geometry>

namespace dfm {

namespace {

constexpr double kMargin = 1e-6;  // of the circumradius

std::uint64_t cell_key(const Eigen::Array3d& q) {
  const auto u = [](double v) { return static_cast<std::uint64_t>(static_cast<std::int64_t>(v) + (1 << 20)) & 0x1FFFFF; };
  return u(q[0]) << 42 | u(q[1]) << 21 | u(q[2]);
}

Eigen::RowVector3d point_of(const Delaunay3::Vertex_handle& v) {
  return Eigen::RowVector3d(v->point().x(), v->point().y(), v->point().z());
}

}  // namespace

Eigen::RowVector3d circumcentre(const Eigen::RowVector3d& a, const Eigen::RowVector3d& b, const Eigen::RowVector3d& c) {
  const Eigen::RowVector3d ab = b - a, ac = c - a, nrm = ab.cross(ac);
  return a + (nrm.cross(ab) * ac.squaredNorm() + ac.cross(nrm) * ab.squaredNorm()) / (2 * nrm.squaredNorm());
}

FaceProtection::FaceProtection(const ConformingSurface& s, const SurfaceDelaunay& d) {
  for (int f = 0; f < s.F.rows(); ++f) {
    Delaunay3::Cell_handle c;
    int i = 0, j = 0, k = 0;
    const auto &va = d.vertex[s.F(f, 0)], &vb = d.vertex[s.F(f, 1)], &vc = d.vertex[s.F(f, 2)];
    const bool is_face = d.dt.is_facet(va, vb, vc, c, i, j, k);
    const Eigen::RowVector3d a = point_of(va), b = point_of(vb), cc = point_of(vc), nrm = (b - a).cross(cc - a);
    const double n2 = nrm.squaredNorm();
    if (!(n2 > 0)) continue;
    Face face;
    face.centre = circumcentre(a, b, cc);
    face.normal = nrm / std::sqrt(n2);
    face.R2 = (face.centre - a).squaredNorm();
    face.row = f;
    face.lo = -HUGE_VAL, face.hi = HUGE_VAL;
    if (is_face) {  // the range its two cells' apexes leave (a single sphere where they are co-spherical)
      const int apex = 6 - i - j - k;
      const Delaunay3::Cell_handle other = c->neighbor(apex);
      for (const Delaunay3::Vertex_handle& v : {c->vertex(apex), other->vertex(other->index(c))})
        if (!d.dt.is_infinite(v)) std::tie(face.lo, face.hi) = narrowed(face, point_of(v));
    }
    if (!(face.lo <= face.hi)) {  // not a face (or numerically not): keep points away instead
      face.missing = true;
      face.lo = face.hi = 0;
      face.R2 *= 4;
    }
    faces_.push_back(face);
  }
  if (faces_.empty()) return;
  // Index each face by the bounding box of its largest empty spheres (the range's ends); a face
  // reaching more than 512 cells (a hull face's range is unbounded) is checked for every point.
  std::vector<double> r;
  for (const Face& f : faces_) r.push_back(f.missing ? f.R2 / 4 : f.R2);
  std::nth_element(r.begin(), r.begin() + r.size() / 2, r.end());
  cell_ = std::max(1e-300, 4 * std::sqrt(r[r.size() / 2]));
  for (int b = 0; b < static_cast<int>(faces_.size()); ++b) {
    const Face& f = faces_[b];
    Eigen::Array3d lo = Eigen::Array3d::Constant(HUGE_VAL), hi = -lo;
    for (const double sh : {f.lo, f.hi}) {
      const double rad = std::sqrt(f.R2 + sh * sh) * (1 + kMargin);
      const Eigen::Array3d c = (f.centre + sh * f.normal).array().transpose();
      lo = lo.min(c - rad), hi = hi.max(c + rad);
    }
    lo = (lo / cell_).floor(), hi = (hi / cell_).floor();
    if (!(lo.allFinite() && hi.allFinite()) || (hi - lo + 1).prod() > 512) {
      large_.push_back(b);
      continue;
    }
    for (double x = lo[0]; x <= hi[0]; ++x)
      for (double y = lo[1]; y <= hi[1]; ++y)
        for (double z = lo[2]; z <= hi[2]; ++z) grid_[cell_key(Eigen::Array3d(x, y, z))].push_back(b);
  }
}

template <class Visit>
bool FaceProtection::visit_near(const Eigen::RowVector3d& p, const Visit& visit) const {
  for (const int b : large_)
    if (!visit(b)) return false;
  if (grid_.empty()) return true;
  const auto it = grid_.find(cell_key((p.array() / cell_).floor().transpose()));
  if (it == grid_.end()) return true;
  for (const int b : it->second)
    if (!visit(b)) return false;
  return true;
}

std::pair<double, double> FaceProtection::narrowed(const Face& f, const Eigen::RowVector3d& p) {
  // p is inside the spheres with s > bound on the positive side (h > 0), s < bound on the negative
  // side; where h = 0, inside all of them when within the circumcircle's cylinder, else none.
  const double h = f.normal.dot(p - f.centre), e = (p - f.centre).squaredNorm() - f.R2;
  if (h > 0) return {f.lo, std::min(f.hi, e / (2 * h))};
  if (h < 0) return {std::max(f.lo, e / (2 * h)), f.hi};
  if (e < 0) return {HUGE_VAL, -HUGE_VAL};
  return {f.lo, f.hi};
}

bool FaceProtection::admit(const Eigen::RowVector3d& p, bool commit) {
  struct Cut {
    int face;
    double lo, hi;
  };
  std::vector<Cut> cuts;
  const bool ok = visit_near(p, [&](int b) {
    const Face& f = faces_[b];
    if (f.missing) return !((p - f.centre).squaredNorm() < f.R2);
    const auto [lo, hi] = narrowed(f, p);
    if (lo == f.lo && hi == f.hi) return true;
    if (!(lo + kMargin * std::sqrt(f.R2) <= hi)) return false;
    cuts.push_back({b, lo, hi});
    return true;
  });
  if (!ok) return false;
  if (commit)
    for (const Cut& c : cuts) faces_[c.face].lo = c.lo, faces_[c.face].hi = c.hi;
  return true;
}

}  // namespace dfm
