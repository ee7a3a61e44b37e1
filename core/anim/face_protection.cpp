#include "core/anim/face_protection.h"

#include <algorithm>
#include <cmath>

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

FaceProtection::FaceProtection(const ConformingSurface& s, const SurfaceDelaunay& d) {
  for (int f = 0; f < s.F.rows(); ++f) {
    Delaunay3::Cell_handle c;
    int i, j, k;
    const auto &va = d.vertex[s.F(f, 0)], &vb = d.vertex[s.F(f, 1)], &vc = d.vertex[s.F(f, 2)];
    const bool is_face = d.dt.is_facet(va, vb, vc, c, i, j, k);
    const Eigen::RowVector3d a = point_of(va), ab = point_of(vb) - a, ac = point_of(vc) - a, nrm = ab.cross(ac);
    const double n2 = nrm.squaredNorm();
    if (!(n2 > 0)) continue;
    Face face;
    face.centre = a + (nrm.cross(ab) * ac.squaredNorm() + ac.cross(nrm) * ab.squaredNorm()) / (2 * n2);
    face.normal = nrm / std::sqrt(n2);
    face.R2 = (face.centre - a).squaredNorm();
    face.row = f;
    face.lo = -HUGE_VAL, face.hi = HUGE_VAL;
    faces_.push_back(face);
    bool kept = is_face;
    if (is_face) {
      const int apex = 6 - i - j - k;
      const Delaunay3::Cell_handle other = c->neighbor(apex);
      for (const Delaunay3::Vertex_handle& v : {c->vertex(apex), other->vertex(other->index(c))})
        kept = kept && (d.dt.is_infinite(v) || admit(point_of(v)));
    }
    if (!kept) {  // not a face, or one only co-spherical points hold: keep points away instead
      ++unprotected_;
      Face& f = faces_.back();
      f.missing = true;
      f.lo = f.hi = 0;
      f.R2 = 4 * face.R2;
    }
  }
  indexed_ = true;
  if (faces_.empty()) return;
  // Index each face by the bounding box of its largest empty spheres (the range's ends), capped.
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

std::vector<int> FaceProtection::candidates(const Eigen::RowVector3d& p) const {
  std::vector<int> out = large_;
  if (!grid_.empty()) {
    const auto it = grid_.find(cell_key((p.array() / cell_).floor().transpose()));
    if (it != grid_.end()) out.insert(out.end(), it->second.begin(), it->second.end());
  }
  return out;
}

bool FaceProtection::admit(const Eigen::RowVector3d& p, bool commit) {
  // Offsets s with p inside the sphere: s > bound where p is on the positive side (h > 0), s < bound
  // on the negative side, every s where h = 0 and p is inside the circumcircle's cylinder.
  struct Cut {
    int face;
    double lo, hi;
  };
  std::vector<Cut> cuts;
  // While constructing: the last face's own apexes.
  const std::vector<int> near = indexed_ ? candidates(p) : std::vector<int>{static_cast<int>(faces_.size()) - 1};
  for (const int b : near) {
    const Face& f = faces_[b];
    const double e = (p - f.centre).squaredNorm() - f.R2;
    if (f.missing) {
      if (e < 0) return false;
      continue;
    }
    const double h = f.normal.dot(p - f.centre);
    const double margin = kMargin * std::sqrt(f.R2);
    double lo = f.lo, hi = f.hi;
    if (h > 0) hi = std::min(hi, e / (2 * h));
    else if (h < 0) lo = std::max(lo, e / (2 * h));
    else if (e < 0) return false;
    if (lo == f.lo && hi == f.hi) continue;
    if (!(lo + margin <= hi)) return false;
    cuts.push_back({b, lo, hi});
  }
  if (commit)
    for (const Cut& c : cuts) faces_[c.face].lo = c.lo, faces_[c.face].hi = c.hi;
  return true;
}

}  // namespace dfm
