#include "core/bind/qp.h"

#include "core/bind/cholmod_view.h"

#include "core/util/hash.h"

#include <cholmod.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <unordered_set>
#include <utility>
#include <vector>

#include "core/util/error.h"

namespace dfm {

namespace {

// PDAS iterations before the monotone fallback, and face solves of both together.
constexpr int kMaxPdasIterations = 60;
constexpr int kMaxIterations = 2000;
// Sweeps after a face, per variable of the face, when that exceeds smoothing_sweeps: the sweeps that pay
// for themselves grow with the face (hand.mesh's ~4K-variable faces want ~20, armadillo's ~40K ~250).
constexpr double kSweepsPerFreeVariable = 0.006;



}  // namespace

// ---------------------------------------------------------------------------------------------- helpers

Eigen::SparseMatrix<double> principal_submatrix(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXi& idx) {
  // Gathered straight into compressed columns (no triplets: this runs on the 71K-vertex armadillo).
  std::vector<int> map(A.rows(), -1);
  for (int k = 0; k < idx.size(); ++k) map[idx(k)] = k;
  const bool increasing = std::is_sorted(idx.data(), idx.data() + idx.size());
  const int m = static_cast<int>(idx.size());
  Eigen::SparseMatrix<double> S(m, m);
  long nnz = 0;
  for (int k = 0; k < m; ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, idx(k)); it; ++it) nnz += map[it.row()] >= 0;
  S.resizeNonZeros(nnz);
  int* outer = S.outerIndexPtr();
  int* inner = S.innerIndexPtr();
  double* values = S.valuePtr();
  std::vector<std::pair<int, double>> col;
  long pos = 0;
  outer[0] = 0;
  for (int k = 0; k < m; ++k) {
    const long begin = pos;
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, idx(k)); it; ++it)
      if (map[it.row()] >= 0) inner[pos] = map[it.row()], values[pos] = it.value(), ++pos;
    if (!increasing) {  // A's columns are sorted; so are these if idx is
      col.clear();
      for (long p = begin; p < pos; ++p) col.emplace_back(inner[p], values[p]);
      std::sort(col.begin(), col.end());
      for (long p = begin; p < pos; ++p) inner[p] = col[p - begin].first, values[p] = col[p - begin].second;
    }
    outer[k + 1] = static_cast<int>(pos);
  }
  return S;
}

OrderedLower ordered_lower(const Eigen::SparseMatrix<double>& H, std::vector<int> perm) {
  const int n = static_cast<int>(H.rows());
  if (H.cols() != n || static_cast<int>(perm.size()) != n)
    throw Error("box QP: the ordering does not match the matrix");
  std::vector<int> pos(n, -1);
  for (int k = 0; k < n; ++k) {
    if (perm[k] < 0 || perm[k] >= n || pos[perm[k]] >= 0) throw Error("box QP: the ordering is not a permutation");
    pos[perm[k]] = k;
  }
  OrderedLower L;
  L.perm = std::move(perm);
  L.colptr.assign(n + 1, 0);
  for (int c = 0; c < n; ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(H, L.perm[c]); it; ++it) L.colptr[c + 1] += pos[it.row()] >= c;
  for (int c = 0; c < n; ++c) L.colptr[c + 1] += L.colptr[c];
  L.rows.resize(L.colptr[n]);
  L.values.resize(L.colptr[n]);
  std::vector<std::pair<int, double>> col;
  for (int c = 0; c < n; ++c) {
    col.clear();
    for (Eigen::SparseMatrix<double>::InnerIterator it(H, L.perm[c]); it; ++it)
      if (pos[it.row()] >= c) col.emplace_back(pos[it.row()], it.value());
    std::sort(col.begin(), col.end());
    for (size_t k = 0; k < col.size(); ++k) L.rows[L.colptr[c] + k] = col[k].first, L.values[L.colptr[c] + k] = col[k].second;
  }
  return L;
}

namespace {

// The lower triangle of H in elimination order: column c holds the entries begin[c] .. end[c] of rows
// (elimination positions >= c, sorted) and values; variable perm[c] (c when perm is null) is eliminated
// c-th. Views either an OrderedLower or H itself when H is already in elimination order.
struct LowerView {
  int n = 0;
  const int* perm = nullptr;
  const int* begin = nullptr;
  const int* end = nullptr;
  const int* rows = nullptr;
  const double* values = nullptr;
};

// Factorizes and solves principal submatrices H_FF (the faces of the box) in the elimination order of a
// fixed ordering of H: the lower triangle of H_FF is gathered straight into CHOLMOD's column format in
// that order (no triplets, no AMD per face), into buffers reused across iterations.
class FaceSolver {
 public:
  explicit FaceSolver(const LowerView& H) : H_(H) {
    cholmod_start(&c_);
    c_.print = 0;
    c_.error_handler = nullptr;
    c_.nmethods = 1;
    c_.method[0].ordering = CHOLMOD_NATURAL;  // the matrix handed over is already in elimination order
    c_.supernodal = CHOLMOD_AUTO;
    // The shared ordering is already a postorder of the whole matrix's elimination tree (a face's tree
    // is near one): skipping CHOLMOD's own postordering saves its transposes.
    c_.postorder = 0;
    loc_.assign(H.n, -1);
  }
  ~FaceSolver() {
    if (L_) cholmod_free_factor(&L_, &c_);
    cholmod_finish(&c_);
  }
  FaceSolver(const FaceSolver&) = delete;
  FaceSolver& operator=(const FaceSolver&) = delete;

  int last_size() const { return L_ ? static_cast<int>(L_->n) : 0; }  // variables in the last face

  // status[i] == 0: variable i is in the face. rhs: full-length; returns x_F = H_FF^-1 rhs_F scattered
  // into out (entries outside F untouched).
  void solve(const std::vector<signed char>& status, const Eigen::VectorXd& rhs, Eigen::VectorXd& out) {
    const int* perm = H_.perm;
    const int* hi = H_.rows;
    const double* hx = H_.values;
    const int n = H_.n;
    auto var = [perm](int c) { return perm ? perm[c] : c; };
    int nf = 0;
    for (int c = 0; c < n; ++c) loc_[c] = status[var(c)] == 0 ? nf++ : -1;
    Ap_.assign(nf + 1, 0);
    Ai_.clear();
    Ax_.clear();
    for (int c = 0, k = 0; c < n; ++c) {
      if (loc_[c] < 0) continue;
      for (int p = H_.begin[c]; p < H_.end[c]; ++p)
        if (loc_[hi[p]] >= 0) Ai_.push_back(loc_[hi[p]]), Ax_.push_back(hx[p]);
      Ap_[++k] = static_cast<int>(Ai_.size());
    }
    cholmod_sparse A = cholmod_lower_view(nf, Ap_.data(), Ai_.data(), Ax_.data());
    if (L_) cholmod_free_factor(&L_, &c_);
    L_ = cholmod_analyze(&A, &c_);
    if (!L_) throw Error("sparse Cholesky: analysis failed (out of memory?)");
    cholmod_factorize(&A, L_, &c_);
    if (c_.status == CHOLMOD_NOT_POSDEF || L_->minor < L_->n)
      throw Error(kCholeskyNotPositiveDefinite);
    if (c_.status < 0) throw Error("sparse Cholesky: factorization failed (out of memory?)");
    b_.resize(nf);
    for (int c = 0; c < n; ++c)
      if (loc_[c] >= 0) b_(loc_[c]) = rhs(var(c));
    cholmod_dense bd{};
    bd.nrow = bd.nzmax = bd.d = static_cast<size_t>(nf);
    bd.ncol = 1;
    bd.x = b_.data();
    bd.xtype = CHOLMOD_REAL;
    bd.dtype = CHOLMOD_DOUBLE;
    cholmod_dense* X = cholmod_solve(CHOLMOD_A, L_, &bd, &c_);
    if (!X) throw Error("sparse Cholesky: solve failed (out of memory?)");
    const double* xv = static_cast<const double*>(X->x);
    for (int c = 0; c < n; ++c)
      if (loc_[c] >= 0) out(var(c)) = xv[loc_[c]];
    cholmod_free_dense(&X, &c_);
  }

 private:
  const LowerView H_;
  cholmod_common c_;
  cholmod_factor* L_ = nullptr;
  std::vector<int> loc_, Ap_, Ai_;
  std::vector<double> Ax_;
  Eigen::VectorXd b_;
};

uint64_t hash_status(const std::vector<signed char>& st) {
  return fnv1a(kFnv1aBasis, st.data(), st.size());
}

// grad = H x + g for a symmetric H stored in full: column i is read as row i, so each entry is a gather
// (a dot product), not Eigen's scatter of x_i times column i.
void gradient(const Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& g, const Eigen::VectorXd& x,
              Eigen::VectorXd& grad) {
  const int n = static_cast<int>(x.size());
  const int* hp = H.outerIndexPtr();
  const int* hi = H.innerIndexPtr();
  const double* hx = H.valuePtr();
  grad.resize(n);
  for (int i = 0; i < n; ++i) {
    double s = g(i);
    for (int p = hp[i]; p < hp[i + 1]; ++p) s += hx[p] * x(hi[p]);
    grad(i) = s;
  }
}

// grad += H (y - x) where y differs from x in a few entries (a sparse update of the gradient).
void update_gradient(const Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& x, const Eigen::VectorXd& y,
                     Eigen::VectorXd& grad) {
  const int* hp = H.outerIndexPtr();
  const int* hi = H.innerIndexPtr();
  const double* hx = H.valuePtr();
  for (int j = 0; j < x.size(); ++j) {
    const double d = y(j) - x(j);
    if (d != 0.0)
      for (int p = hp[j]; p < hp[j + 1]; ++p) grad(hi[p]) += hx[p] * d;
  }
}

// Natural residual in the Jacobi metric (see box_qp_kkt_residual) from the gradient at x; hd > 0.
double kkt_residual_from_gradient(const Eigen::VectorXd& lo, const Eigen::VectorXd& hi, const Eigen::VectorXd& hd,
                                  const Eigen::VectorXd& x, const Eigen::VectorXd& grad) {
  double r = 0;
  for (int i = 0; i < x.size(); ++i) {
    // How far one diagonal Newton step, projected on the box, would move x_i. Zero iff stationary
    // (free), or the gradient points out of the box (at a bound).
    const double step = std::min(std::max(x(i) - grad(i) / hd(i), lo(i)), hi(i));
    double v = std::abs(step - x(i));
    if (x(i) < lo(i)) v = std::max(v, lo(i) - x(i));
    if (x(i) > hi(i)) v = std::max(v, x(i) - hi(i));
    r = std::max(r, v);
  }
  return r;
}

// Projected successive over-relaxation on a work set: a sweep visits, in index order, only the variables
// whose neighbours moved by more than `threshold` in the previous sweep (starting from those with a KKT
// step above it). Each update moves x_i by omega times its exact 1-D minimizing step, clipped to the box:
// for 0 < omega < 2 the 1-D quadratic is lower there than at x_i and the clipped point lies between the
// two, so the objective never increases.
// The work set is a byte map scanned over the range it spans (no sorting of work lists).
void projected_gauss_seidel(const Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& g,
                            const Eigen::VectorXd& lo, const Eigen::VectorXd& hi, const Eigen::VectorXd& hd,
                            const Eigen::VectorXd& grad, int sweeps, double omega, double threshold,
                            Eigen::VectorXd& x) {
  const int n = static_cast<int>(x.size());
  const int* hp = H.outerIndexPtr();
  const int* hi_ = H.innerIndexPtr();
  const double* hx = H.valuePtr();
  std::vector<char> cur(n, 0), next(n, 0);
  int first = n, last = -1;
  {  // grad: the gradient at the incoming x
    for (int i = 0; i < n; ++i) {
      const double step = std::min(std::max(x(i) - grad(i) / hd(i), lo(i)), hi(i)) - x(i);
      if (std::abs(step) > threshold) cur[i] = 1, first = std::min(first, i), last = i;
    }
  }
  for (int sweep = 0; sweep < sweeps && first <= last; ++sweep) {
    int nfirst = n, nlast = -1;
    for (int i = first; i <= last; ++i) {
      if (!cur[i]) continue;
      cur[i] = 0;
      double gi = g(i);
      for (int p = hp[i]; p < hp[i + 1]; ++p) gi += hx[p] * x(hi_[p]);
      const double xi = std::min(std::max(x(i) - omega * gi / hd(i), lo(i)), hi(i));
      const double d = xi - x(i);
      x(i) = xi;
      if (std::abs(d) > threshold) {
        for (int p = hp[i]; p < hp[i + 1]; ++p) {
          next[hi_[p]] = 1;
          nfirst = std::min(nfirst, hi_[p]);
          nlast = std::max(nlast, hi_[p]);
        }
      }
    }
    cur.swap(next);
    first = nfirst, last = nlast;
  }
}


// ---------------------------------------------------------------------------------------- the solver

// The argument checks, in the order their messages have always come.
void check_box_qp_arguments(const Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& g,
                            const Eigen::VectorXd& lo, const Eigen::VectorXd& hi, const Eigen::VectorXd& x0,
                            const BoxQPOptions& opts) {
  const int n = static_cast<int>(g.size());
  if (H.rows() != n || H.cols() != n || lo.size() != n || hi.size() != n || (x0.size() != 0 && x0.size() != n))
    throw Error("box QP: inconsistent sizes");
  if ((lo.array() > hi.array()).any()) throw Error("box QP: a lower bound exceeds its upper bound");
  if (!(opts.smoothing_relaxation > 0 && opts.smoothing_relaxation < 2))
    throw Error("box QP: the smoothing relaxation factor must lie in (0, 2)");
}

// H's lower triangle in elimination order, as the face solves read it: H itself when it is already in
// that order, else an OrderedLower (the caller's, or one built here with an AMD ordering). Owns what
// the view points into, so it is neither copied nor moved.
struct FaceMatrix {
  FaceMatrix(const Eigen::SparseMatrix<double>& H, const BoxQPOptions& opts) {
    const int n = static_cast<int>(H.rows());
    view.n = n;
    if (opts.in_elimination_order && H.isCompressed()) {
      const int* hp = H.outerIndexPtr();
      const int* hi_ = H.innerIndexPtr();
      diagonal.resize(n);
      for (int c = 0; c < n; ++c) diagonal[c] = static_cast<int>(std::lower_bound(hi_ + hp[c], hi_ + hp[c + 1], c) - hi_);
      view.begin = diagonal.data();
      view.end = hp + 1;
      view.rows = hi_;
      view.values = H.valuePtr();
    } else {
      if (!opts.ordered) own = ordered_lower(H, fill_reducing_ordering(H));
      const OrderedLower& ordered = opts.ordered ? *opts.ordered : own;
      if (static_cast<int>(ordered.perm.size()) != n) throw Error("box QP: the ordering does not match the matrix");
      view.perm = ordered.perm.data();
      view.begin = ordered.colptr.data();
      view.end = ordered.colptr.data() + 1;
      view.rows = ordered.rows.data();
      view.values = ordered.values.data();
    }
  }
  FaceMatrix(const FaceMatrix&) = delete;
  FaceMatrix& operator=(const FaceMatrix&) = delete;

  OrderedLower own;
  std::vector<int> diagonal;  // where each column's lower part starts, when H is read directly
  LowerView view;
};

// One solve: the problem, the iterate and its active set, and the face solver, which the primal-dual
// active set iterations and the monotone fallback share.
struct BoxQpSolve {
  BoxQpSolve(const Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& g, const Eigen::VectorXd& lo,
             const Eigen::VectorXd& hi, const Eigen::VectorXd& x0, const BoxQPOptions& opts, const LowerView& faces)
      : H(H), g(g), lo(lo), hi(hi), opts(opts), n(static_cast<int>(g.size())), face(faces), st(n, 0),
        x(x0.size() ? x0 : lo), xa(n), r(n), hd(H.diagonal()), sweeping(opts.smoothing_sweeps > 0),
        relative(opts.smoothing_threshold_relative) {
    status_from_position();
    if (!(hd.array() > 0).all()) throw Error("box QP: the matrix has a non-positive diagonal entry");
  }

  void presmooth();
  bool primal_dual_active_set();
  bool monotone_fallback();
  BoxQPResult result(bool done);

  void check_cancel() const {
    if (opts.cancel && opts.cancel->load()) throw Cancelled();
  }
  void status_from_position();
  void solve_face(Eigen::VectorXd& out);
  int update_active_set();
  bool sweep_after_face(double kkt);
  double step_to_first_bound(const Eigen::VectorXd& xt) const;
  void activate_reached_bounds();
  int release_wrong_signs();

  const Eigen::SparseMatrix<double>& H;
  const Eigen::VectorXd& g;
  const Eigen::VectorXd& lo;
  const Eigen::VectorXd& hi;
  const BoxQPOptions& opts;
  const int n;
  FaceSolver face;
  std::vector<signed char> st;  // -1 at lower bound, +1 at upper bound, 0 free
  Eigen::VectorXd x, grad;
  Eigen::VectorXd xa, r;        // solve_face's buffers
  const Eigen::VectorXd hd;     // H's diagonal, > 0
  bool sweeping;                // projected Gauss-Seidel sweeps after each PDAS face
  double relative;              // see smoothing_threshold_relative
  double previous_kkt = std::numeric_limits<double>::infinity();
  BoxQPResult res;
};

// Each variable's status read off where x is: at a bound, or free.
void BoxQpSolve::status_from_position() {
  for (int i = 0; i < n; ++i) st[i] = x(i) <= lo(i) ? -1 : (x(i) >= hi(i) ? 1 : 0);
}

// Minimizer over the free variables with the others at their bounds.
void BoxQpSolve::solve_face(Eigen::VectorXd& out) {
  bool any_free = false;
  for (int i = 0; i < n; ++i) {
    xa(i) = st[i] == 0 ? 0.0 : (st[i] < 0 ? lo(i) : hi(i));
    any_free = any_free || st[i] == 0;
  }
  out = xa;
  ++res.iterations;
  if (!any_free) return;
  const int* hp = H.outerIndexPtr();
  const int* hi_ = H.innerIndexPtr();
  const double* hx = H.valuePtr();
  r = -g;  // -(H xa + g), H xa summed over xa's nonzeros only (most bound variables sit at 0)
  for (int j = 0; j < n; ++j)
    if (xa(j) != 0.0)
      for (int p = hp[j]; p < hp[j + 1]; ++p) r(hi_[p]) -= hx[p] * xa(j);
  face.solve(st, r, out);
}

// Sweeps from the start before the first face: a start carried from a coarser mesh is smooth on the
// coarse scale but off on the fine one, which is what the sweeps fix first (multigrid's smoothing after
// prolongation), so the first face is read off a better active set.
void BoxQpSolve::presmooth() {
  x = x.cwiseMax(lo).cwiseMin(hi);
  gradient(H, g, x, grad);
  const int sweeps = std::max(opts.smoothing_sweeps, static_cast<int>(opts.presmoothing_sweeps_per_variable * n));
  const double threshold = std::max(0.1 * opts.tolerance, opts.smoothing_threshold_relative *
                                                              kkt_residual_from_gradient(lo, hi, hd, x, grad));
  projected_gauss_seidel(H, g, lo, hi, hd, grad, sweeps, opts.smoothing_relaxation, threshold, x);
  status_from_position();
}

// PDAS's next active set from the face solution x and its gradient: a free variable past a bound is
// fixed there, a bound one whose gradient points into the box is freed. Returns how many changed.
int BoxQpSolve::update_active_set() {
  const double tau = 0.1 * opts.tolerance;  // in the Jacobi-scaled units of the KKT residual
  int changes = 0;
  for (int i = 0; i < n; ++i) {
    signed char s = st[i];
    const double eps = 1e-13 * (hi(i) - lo(i));
    if (s == 0) {
      if (x(i) < lo(i) - eps) s = -1;
      else if (x(i) > hi(i) + eps) s = 1;
    } else if (s < 0 && grad(i) < -tau * hd(i)) {
      s = 0;
    } else if (s > 0 && grad(i) > tau * hd(i)) {
      s = 0;
    }
    if (s != st[i]) ++changes, st[i] = s;
  }
  return changes;
}

// The face solve is exact but releases bound variables only where the gradient reaches them (a 2-ring
// stencil), so the support creeps outwards a ring or two per factorization. A few projected
// Gauss-Seidel sweeps, confined to where the iterate still moves, carry that front many rings for the
// cost of a fraction of one factorization; the next face is read off the swept iterate. kkt: the
// residual of the face's (clipped) solution. True when the swept iterate is a KKT point.
bool BoxQpSolve::sweep_after_face(double kkt) {
  const int sweeps = std::max(opts.smoothing_sweeps, static_cast<int>(kSweepsPerFreeVariable * face.last_size()));
  // Skipping small moves speeds up sweeps that make progress; once a face fails to halve the
  // residual, the active set is oscillating near the front: full sweeps from then on.
  if (kkt > 0.5 * previous_kkt) relative = 0;
  previous_kkt = kkt;
  const double threshold = std::max(0.1 * opts.tolerance, relative * kkt);
  projected_gauss_seidel(H, g, lo, hi, hd, grad, sweeps, opts.smoothing_relaxation, threshold, x);
  gradient(H, g, x, grad);
  if (kkt_residual_from_gradient(lo, hi, hd, x, grad) <= opts.tolerance) return true;
  status_from_position();
  return false;
}

// Primal-dual active set. True at a KKT point; false when it cycles without sweeps or runs out of
// iterations (the monotone fallback goes on from there).
bool BoxQpSolve::primal_dual_active_set() {
  std::unordered_set<uint64_t> seen;
  Eigen::VectorXd xc;
  for (int it = 0; it < kMaxPdasIterations; ++it) {
    check_cancel();
    solve_face(x);
    gradient(H, g, x, grad);
    const int changes = update_active_set();
    // The tail of PDAS moves a few variables with tiny multipliers: stop as soon as the clipped iterate
    // is a KKT point to the tolerance (checked exactly, not estimated).
    xc = x.cwiseMax(lo).cwiseMin(hi);
    update_gradient(H, x, xc, grad);  // now the gradient at xc
    x.swap(xc);
    const double kkt = kkt_residual_from_gradient(lo, hi, hd, x, grad);
    if (changes == 0 || kkt <= opts.tolerance) return true;
    if (sweeping && sweep_after_face(kkt)) return true;
    if (!seen.insert(hash_status(st)).second) {
      // Cycling. The sweeps move the active set by other rules than PDAS's own: first try without them
      // (plain PDAS from here, locally fast), and go monotone if that cycles too.
      if (!sweeping) return false;
      sweeping = false;
      res.sweeps_dropped = true;
      seen.clear();
    }
  }
  return false;
}

// Ratio test: the largest step in [0, 1] from x towards the face solution xt that keeps every free
// variable in the box.
double BoxQpSolve::step_to_first_bound(const Eigen::VectorXd& xt) const {
  double alpha = 1.0;
  for (int i = 0; i < n; ++i) {
    if (st[i] != 0) continue;
    const double d = xt(i) - x(i);
    if (xt(i) < lo(i) && d < 0) alpha = std::min(alpha, (lo(i) - x(i)) / d);
    if (xt(i) > hi(i) && d > 0) alpha = std::min(alpha, (hi(i) - x(i)) / d);
  }
  return std::max(alpha, 0.0);
}

// Fixes the free variables a shortened step brought to a bound (to rounding) at that bound.
void BoxQpSolve::activate_reached_bounds() {
  for (int i = 0; i < n; ++i) {
    if (st[i] != 0) continue;
    const double eps = 1e-12 * (hi(i) - lo(i));
    if (x(i) <= lo(i) + eps) st[i] = -1, x(i) = lo(i);
    else if (x(i) >= hi(i) - eps) st[i] = 1, x(i) = hi(i);
  }
}

// Frees the bound variables whose gradient points into the box; returns how many.
int BoxQpSolve::release_wrong_signs() {
  const double tau = 0.1 * opts.tolerance;  // in the Jacobi-scaled units of the KKT residual
  int released = 0;
  for (int i = 0; i < n; ++i)
    if ((st[i] < 0 && grad(i) < -tau * hd(i)) || (st[i] > 0 && grad(i) > tau * hd(i))) st[i] = 0, ++released;
  return released;
}

// Primal active set with a ratio test: the objective strictly decreases, so it cannot cycle. True at a
// KKT point, false at the iteration cap.
bool BoxQpSolve::monotone_fallback() {
  x = x.cwiseMax(lo).cwiseMin(hi);
  status_from_position();
  Eigen::VectorXd xt;
  while (res.iterations < kMaxIterations) {
    check_cancel();
    ++res.fallback_iterations;
    solve_face(xt);
    const double alpha = step_to_first_bound(xt);
    for (int i = 0; i < n; ++i)
      if (st[i] == 0) x(i) += alpha * (xt(i) - x(i));
    if (alpha < 1.0) {
      activate_reached_bounds();
      continue;
    }
    gradient(H, g, x, grad);
    if (release_wrong_signs() == 0) return true;
  }
  return false;
}

BoxQPResult BoxQpSolve::result(bool done) {
  x = x.cwiseMax(lo).cwiseMin(hi);
  res.x = x;
  res.kkt_residual = box_qp_kkt_residual(H, g, lo, hi, x);
  res.converged = done && res.kkt_residual <= opts.tolerance;
  res.num_free = 0;
  for (int i = 0; i < n; ++i) res.num_free += (x(i) > lo(i) && x(i) < hi(i));
  return res;
}

}  // namespace

double box_qp_kkt_residual(const Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& g, const Eigen::VectorXd& lo,
                           const Eigen::VectorXd& hi, const Eigen::VectorXd& x) {
  if (H.rows() != x.size() || H.cols() != x.size() || g.size() != x.size() || lo.size() != x.size() ||
      hi.size() != x.size())
    throw Error("box QP: inconsistent sizes");
  const Eigen::VectorXd d = H.diagonal();
  if (!(d.array() > 0).all()) throw Error("box QP: the matrix has a non-positive diagonal entry");
  Eigen::VectorXd grad;
  gradient(H, g, x, grad);
  return kkt_residual_from_gradient(lo, hi, d, x, grad);
}

BoxQPResult solve_box_qp(const Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& g, const Eigen::VectorXd& lo,
                         const Eigen::VectorXd& hi, const Eigen::VectorXd& x0, const BoxQPOptions& opts) {
  check_box_qp_arguments(H, g, lo, hi, x0, opts);
  const FaceMatrix faces(H, opts);
  BoxQpSolve qp(H, g, lo, hi, x0, opts, faces.view);  // throws on a non-positive diagonal
  if (qp.sweeping && x0.size() && opts.presmoothing_sweeps_per_variable > 0) qp.presmooth();
  const bool done = qp.primal_dual_active_set() || qp.monotone_fallback();
  return qp.result(done);
}

}  // namespace dfm
