#include "core/bind/weight_mirror.h"

#include <cmath>
#include <limits>
#include <string>

#include "core/bind/closest_surface_point.h"
#include "core/mesh/mesh_info.h"
#include "core/util/error.h"

namespace dfm {
namespace {

bool is_side(char c) { return c == 'l' || c == 'L' || c == 'r' || c == 'R'; }
bool is_separator(char c) { return c == '_' || c == '.' || c == '-' || c == ' '; }
char other_side(char c) {
  switch (c) {
    case 'l': return 'r';
    case 'r': return 'l';
    case 'L': return 'R';
    default: return 'L';
  }
}

// The name a rig gave a handle (not handle_name's generated "bone 3").
std::string given_name(const Rig& rig, const HandleRef& r) {
  switch (r.kind) {
    case HandleKind::Point: return rig.points[r.index].name;
    case HandleKind::Bone: return rig.skeleton.bones[r.index].name;
    case HandleKind::Region: return rig.regions[r.index].name;
    case HandleKind::CageVertex: return "";  // cage vertices share their cage's name: geometry only
  }
  return "";
}

// The points a handle's mirror must match: a bone both joints, the others their pivot.
std::vector<Eigen::Vector3d> pivots(const Rig& rig, const Eigen::MatrixXd& V, const HandleRef& r) {
  switch (r.kind) {
    case HandleKind::Point: return {rig.points[r.index].position};
    case HandleKind::Bone: {
      const Bone& b = rig.skeleton.bones[r.index];
      return {rig.skeleton.joints.row(b.a).transpose(), rig.skeleton.joints.row(b.b).transpose()};
    }
    case HandleKind::CageVertex: return {rig.cages[r.cage].mesh.V.row(r.index).transpose()};
    case HandleKind::Region: {
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      int n = 0;
      for (int v : rig.regions[r.index].vertices)
        if (v >= 0 && v < V.rows()) c += V.row(v).transpose(), ++n;
      return {n ? Eigen::Vector3d(c / n) : c};
    }
  }
  return {};
}

Eigen::Vector3d reflect(const Eigen::Vector3d& p, const Eigen::Vector3d& n, double offset) {
  return p - 2 * (n.dot(p) - offset) * n;
}

}  // namespace

std::string mirrored_name(const std::string& s) {
  const size_t n = s.size();
  if (n >= 2 && is_side(s[0]) && is_separator(s[1])) return other_side(s[0]) + s.substr(1);
  if (n >= 2 && is_side(s[n - 1]) && is_separator(s[n - 2])) return s.substr(0, n - 1) + other_side(s[n - 1]);
  // A whole word: "upper right arm", "LeftEye", "armRight"; not "bright" or "Rightful".
  auto upper = [](char c) { return c >= 'A' && c <= 'Z'; };
  static const std::pair<const char*, const char*> words[] = {
      {"left", "right"}, {"right", "left"}, {"Left", "Right"}, {"Right", "Left"}, {"LEFT", "RIGHT"}, {"RIGHT", "LEFT"}};
  for (const auto& [from, to] : words) {
    const size_t len = std::string(from).size();
    for (size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + 1)) {
      const bool starts = at == 0 || is_separator(s[at - 1]) || (upper(from[0]) && !upper(s[at - 1]));
      const bool ends = at + len == n || is_separator(s[at + len]) || upper(s[at + len]);
      if (starts && ends) return s.substr(0, at) + to + s.substr(at + len);
    }
  }
  return "";
}

std::vector<int> mirror_handles(const Rig& rig, const Eigen::MatrixXd& V, const Eigen::Vector3d& normal,
                                double offset, double tol, std::vector<int>* unmatched) {
  const int nh = num_handles(rig);
  const Eigen::Vector3d n = normal.normalized();
  std::vector<HandleRef> refs;
  std::vector<std::vector<Eigen::Vector3d>> piv;
  for (int h = 0; h < nh; ++h) refs.push_back(handle_ref(rig, h)), piv.push_back(pivots(rig, V, refs[h]));
  std::vector<int> mirror(nh, -1);
  // Names first: the user's explicit left/right.
  for (int h = 0; h < nh; ++h) {
    const std::string want = mirrored_name(given_name(rig, refs[h]));
    if (want.empty()) continue;
    for (int g = 0; g < nh && mirror[h] < 0; ++g)
      if (g != h && refs[g].kind == refs[h].kind && given_name(rig, refs[g]) == want) mirror[h] = g;
  }
  // Then geometry: mutually nearest reflected pivots within tol.
  auto distance = [&](int h, int g) {
    double d = 0;
    for (size_t k = 0; k < piv[h].size(); ++k) d = std::max(d, (reflect(piv[h][k], n, offset) - piv[g][k]).norm());
    return d;
  };
  auto nearest = [&](int h) {
    int best = -1;
    double bd = std::numeric_limits<double>::infinity();
    for (int g = 0; g < nh; ++g)
      if (refs[g].kind == refs[h].kind && piv[g].size() == piv[h].size()) {
        const double d = distance(h, g);
        if (d < bd) bd = d, best = g;
      }
    return bd <= tol ? best : -1;
  };
  for (int h = 0; h < nh; ++h) {
    if (mirror[h] >= 0) continue;
    const int g = nearest(h);
    if (g >= 0 && (g == h || nearest(g) == h) && (mirror[g] < 0 || mirror[g] == h)) mirror[h] = g;
  }
  // An involution or nothing: a handle whose partner points elsewhere (duplicate names) keeps itself.
  for (int h = 0; h < nh; ++h)
    if (mirror[h] >= 0 && mirror[mirror[h]] != h) mirror[h] = -1;
  for (int h = 0; h < nh; ++h) {
    if (mirror[h] >= 0) continue;
    mirror[h] = h;
    double off_plane = 0;
    for (const Eigen::Vector3d& p : piv[h]) off_plane = std::max(off_plane, std::abs(n.dot(p) - offset));
    if (unmatched && off_plane > tol) unmatched->push_back(h);
  }
  return mirror;
}

Eigen::MatrixXd mirror_weights(const Eigen::MatrixXd& W, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                               const Rig& rig, const std::vector<bool>& fixed, const MirrorOptions& opts,
                               MirrorReport* report) {
  if (!(opts.normal.norm() > 0) || !opts.normal.allFinite()) throw Error("mirror: the plane normal is zero");
  if (!(opts.tolerance >= 0) || !std::isfinite(opts.offset)) throw Error("mirror: tolerance must be >= 0, offset finite");
  if (W.rows() != V.rows() || W.cols() != num_handles(rig))
    throw Error("mirror: weights are " + std::to_string(W.rows()) + " x " + std::to_string(W.cols()) + " for " +
                std::to_string(V.rows()) + " vertices and " + std::to_string(num_handles(rig)) + " handles");
  if (!fixed.empty() && fixed.size() != static_cast<size_t>(W.rows()))
    throw Error("fixed-row flags: " + std::to_string(fixed.size()) + " for " + std::to_string(W.rows()) + " rows");
  const Eigen::Vector3d n = opts.normal.normalized();
  const double diag = bounding_box(V).diagonal().norm(), tol = opts.tolerance * diag, plane_band = 1e-6 * diag;
  MirrorReport rep;
  rep.handle_mirror = mirror_handles(rig, V, n, opts.offset, tol, &rep.unmatched_handles);
  const SurfaceLocator locator(V, F, tol);
  Eigen::MatrixXd out = W;
  for (int i = 0; i < W.rows(); ++i) {
    if (!fixed.empty() && fixed[i]) continue;
    const Eigen::Vector3d p = V.row(i).transpose();
    const double side = n.dot(p) - opts.offset;
    const bool on_plane = std::abs(side) <= plane_band;
    if ((opts.mode == MirrorMode::PositiveToNegative && side > plane_band) ||
        (opts.mode == MirrorMode::NegativeToPositive && side < -plane_band))
      continue;  // a source vertex
    const SurfaceSample s = locator.closest(reflect(p, n, opts.offset));
    if (!s.found()) {
      ++rep.vertices_unmatched;
      continue;
    }
    for (int h = 0; h < W.cols(); ++h) {
      const int g = rep.handle_mirror[h];
      double x = 0;
      for (int k = 0; k < 3; ++k) x += s.weight[k] * W(s.vertex[k], g);
      out(i, h) = on_plane && opts.mode != MirrorMode::Flip ? 0.5 * (W(i, h) + x) : x;
    }
    if (out.row(i) != W.row(i)) ++rep.vertices_changed;
  }
  if (report) *report = rep;
  return out;
}

}  // namespace dfm
