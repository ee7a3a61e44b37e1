// The Sculpt tool's document members (document.h, sculpt_session.h): the session's region, handle and
// move, solved by core/sculpt/variational_deform.h with one factorization per region choice.
#include <algorithm>
#include <cmath>
#include <string>

#include "core/scene/document.h"
#include "core/scene/document_parts.h"
#include "core/sculpt/variational_deform.h"
#include "core/util/error.h"

namespace dfm {

int SculptSession::region_count() const { return static_cast<int>(std::count(region.begin(), region.end(), 1)); }

struct Document::SculptSolver {
  SculptSolver(const SculptSession& s, const std::vector<int>& fixed)
      : deform(s.base.V, s.base.F, fixed, s.handle, VariationalDeformOptions{s.order}) {}
  VariationalDeform deform;
};

namespace {

void check_dab(const Eigen::Vector3d& center, double radius) {
  document_detail::check_finite(center, "the sculpt point");
  if (!(radius > 0) || !std::isfinite(radius)) throw Error("radius must be > 0");
}

std::vector<int> within(const Eigen::MatrixXd& V, const Eigen::Vector3d& c, double radius) {
  std::vector<int> out;
  for (Eigen::Index v = 0; v < V.rows(); ++v)
    if ((V.row(v).transpose() - c).squaredNorm() <= radius * radius) out.push_back(static_cast<int>(v));
  return out;
}

}  // namespace

SculptSession& Document::sculpt_session() {
  if (sculpt_) return *sculpt_;
  if (s_.surface.num_vertices() == 0) throw Error("sculpting needs a surface: open a mesh first");
  auto s = std::make_unique<SculptSession>();
  const int k = key_at(s_.time);
  s->source_key = k >= 0 && s_.keys[k].is_mesh() ? k : -1;
  const TriMesh& from = s->source_key >= 0 ? s_.keys[k].mesh : s_.surface;
  s->base = TriMesh{from.V, from.F, {}};
  s->region.assign(static_cast<size_t>(from.V.rows()), 0);
  s->result = from.V;
  s->revision = ++sculpt_revision_;
  sculpt_ = std::move(s);
  return *sculpt_;
}

void Document::sculpt_commit() {
  SculptSession& s = *sculpt_;
  if (s.move.isZero(0)) return;
  s.base.V = s.result;
  s.move.setZero();
  sculpt_solver_.reset();
}

int Document::sculpt_region(const Eigen::Vector3d& center, double radius, bool erase) {
  check_dab(center, radius);
  const bool started = !sculpt_;
  SculptSession& s = sculpt_session();
  const std::vector<int> hit = within(s.result, center, radius);
  if (hit.empty()) {
    if (started) sculpt_.reset();
    throw Error("no surface vertex within " + std::to_string(radius) + " of the point");
  }
  sculpt_commit();
  for (int v : hit) s.region[v] = erase ? 0 : 1;
  // The handle stays inside the region: erased vertices leave it.
  s.handle.erase(std::remove_if(s.handle.begin(), s.handle.end(), [&](int v) { return !s.region[v]; }), s.handle.end());
  sculpt_solver_.reset();
  s.revision = ++sculpt_revision_;
  return static_cast<int>(hit.size());
}

int Document::sculpt_handle(const Eigen::Vector3d& center, double radius) {
  check_dab(center, radius);
  if (!sculpt_ || sculpt_->region_count() == 0) throw Error("paint the free region first (sculpt-region)");
  SculptSession& s = *sculpt_;
  std::vector<int> h;
  for (int v : within(s.result, center, radius))
    if (s.region[v]) h.push_back(v);
  if (h.empty()) throw Error("no vertex of the free region within " + std::to_string(radius) + " of the point");
  sculpt_commit();
  s.handle = std::move(h);
  sculpt_solver_.reset();
  s.revision = ++sculpt_revision_;
  return static_cast<int>(s.handle.size());
}

void Document::sculpt_order(int order) {
  if (order != 2 && order != 3) throw Error("the order is 2 (smooth, C1) or 3 (very smooth, C2), got " + std::to_string(order));
  SculptSession& s = sculpt_session();
  if (s.order == order) return;
  const int before = s.order;
  s.order = order;
  sculpt_solver_.reset();
  if (!s.move.isZero(0)) {
    try {
      sculpt_move(Eigen::Vector3d::Zero());  // the same move, solved in the other order
    } catch (...) {
      s.order = before;
      throw;
    }
  }
  s.revision = ++sculpt_revision_;
}

void Document::sculpt_move(const Eigen::Vector3d& delta) {
  document_detail::check_finite(delta, "the move");
  if (!sculpt_ || sculpt_->handle.empty()) throw Error("pick a handle first (sculpt-handle), inside the free region");
  SculptSession& s = *sculpt_;
  if (!sculpt_solver_) {
    std::vector<int> fixed;
    for (size_t v = 0; v < s.region.size(); ++v)
      if (!s.region[v]) fixed.push_back(static_cast<int>(v));
    // Throws (nothing changed) for a free region that is empty or that nothing holds.
    sculpt_solver_ = std::make_shared<const SculptSolver>(s, fixed);
  }
  const Eigen::Vector3d move = s.move + delta;
  s.result = sculpt_solver_->deform.solve(handle_translation(move.transpose()));
  s.move = move;
  s.revision = ++sculpt_revision_;
}

void Document::sculpt_key(double t) {
  if (!sculpt_) throw Error("nothing sculpted: paint a region, pick a handle and move it first");
  key_mesh(TriMesh{sculpt_->result, sculpt_->base.F, {}}, "sculpt", t);
  sculpt_clear();
}

void Document::sculpt_clear() {
  sculpt_.reset();
  sculpt_solver_.reset();
}

double Document::sculpt_factor_seconds() const { return sculpt_solver_ ? sculpt_solver_->deform.factor_seconds() : 0.0; }

}  // namespace dfm
