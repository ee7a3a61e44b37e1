#include "core/anim/shape_space.h"

#include <cmath>
#include <cstdio>
#include <string>

#include <Eigen/SVD>

#include "core/util/error.h"

namespace dfm {

namespace {

std::string base_name(const std::vector<std::string>& names, int i) {
  return i < static_cast<int>(names.size()) && !names[i].empty() ? names[i] : "base " + std::to_string(i);
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

}  // namespace

ShapeMorph parse_shape_morph(const std::string& name) {
  if (name == "linear") return ShapeMorph::Linear;
  if (name == "arap") return ShapeMorph::Arap;
  throw Error("unknown morph '" + name + "' (linear or arap)");
}

const char* shape_morph_name(ShapeMorph m) { return m == ShapeMorph::Linear ? "linear" : "arap"; }

void check_shape_bases(const std::vector<TriMesh>& bases, const std::vector<std::string>& names) {
  if (bases.size() < 2)
    throw Error("a shape space needs at least 2 bases, got " + std::to_string(bases.size()));
  for (size_t i = 0; i < bases.size(); ++i) {
    const TriMesh& b = bases[i];
    if (b.V.cols() != 3 || b.V.rows() == 0) throw Error(base_name(names, i) + ": no vertices");
    if (!b.V.allFinite()) throw Error(base_name(names, i) + ": a vertex position is not finite");
    if (i == 0) continue;
    if (b.V.rows() != bases[0].V.rows() || b.F.rows() != bases[0].F.rows() || b.F.cols() != bases[0].F.cols() ||
        b.F != bases[0].F)
      throw Error(base_name(names, i) + ": its vertices or triangles differ from " + base_name(names, 0) + "'s (" +
                  std::to_string(b.V.rows()) + " vertices, " + std::to_string(b.F.rows()) + " triangles against " +
                  std::to_string(bases[0].V.rows()) + " and " + std::to_string(bases[0].F.rows()) +
                  "; a shape space needs one connectivity)");
  }
}

void check_shape_coordinates(const Eigen::VectorXd& x, int n) {
  if (x.size() != n)
    throw Error("a shape space of " + std::to_string(n) + " bases needs " + std::to_string(n) + " coordinates, got " +
                std::to_string(x.size()));
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(x(i))) throw Error("coordinate " + std::to_string(i) + " is not finite");
  if (std::abs(x.sum() - 1.0) > 1e-6)
    throw Error("the coordinates sum to " + num(x.sum()) + ", not 1 (they are barycentric: one weight per base)");
}

MorphChain morph_chain(const Eigen::VectorXd& x) {
  if (x.size() == 0) throw Error("a shape space needs coordinates");
  MorphChain c;
  int last = static_cast<int>(x.size()) - 1;
  while (last > 0 && x(last) == 0.0) --last;
  c.start = last;
  const double scale = x.cwiseAbs().sum();
  double tail = x(last);  // S_{k+1}
  for (int k = last - 1; k >= 0; --k) {
    const double s = x(k) + tail;  // S_k
    if (!(std::abs(s) > 1e-9 * scale))
      throw Error("the weights " + std::to_string(k) + ".." + std::to_string(x.size() - 1) +
                  " sum to 0: Eq. 5.31's chain is undefined in this order of the bases (reorder them)");
    const double t = tail / s;
    if (t != 1.0) c.steps.push_back({k, t});
    tail = s;
  }
  return c;
}

Eigen::MatrixXd synthesize_linear(const std::vector<Eigen::MatrixXd>& bases, const Eigen::VectorXd& x) {
  check_shape_coordinates(x, static_cast<int>(bases.size()));
  const MorphChain chain = morph_chain(x);
  Eigen::MatrixXd C = bases[chain.start];
  for (const MorphChain::Step& s : chain.steps) C = linear_interpolation(bases[s.base], C, s.t);
  return C;
}

double ShapeAnalysis::quality() const {
  if (singular_values.size() == 0 || singular_values(0) <= 0) return 0;
  return rank < singular_values.size() ? 0.0 : singular_values(singular_values.size() - 1) / singular_values(0);
}

ShapeAnalysis analyze_linear(const std::vector<Eigen::MatrixXd>& bases, const Eigen::MatrixXd& M) {
  const int n = static_cast<int>(bases.size());
  if (n < 2) throw Error("a shape space needs at least 2 bases, got " + std::to_string(n));
  for (int i = 1; i < n; ++i)
    if (bases[i].rows() != bases[0].rows() || bases[i].cols() != bases[0].cols())
      throw Error("base " + std::to_string(i) + " has " + std::to_string(bases[i].rows()) + " vertices, base 0 " +
                  std::to_string(bases[0].rows()));
  if (M.rows() != bases[0].rows() || M.cols() != bases[0].cols())
    throw Error("the mesh has " + std::to_string(M.rows()) + " vertices, the bases " + std::to_string(bases[0].rows()));
  if (!M.allFinite()) throw Error("a vertex position of the mesh is not finite");
  const Eigen::Index m = M.size();
  // Columns: vec(B_i - B_0); the unknowns are x_1 .. x_{n-1} (B_0 is the space's zero, 5.4).
  Eigen::MatrixXd D(m, n - 1);
  for (int i = 1; i < n; ++i) D.col(i - 1) = Eigen::Map<const Eigen::VectorXd>((bases[i] - bases[0]).eval().data(), m);
  const Eigen::MatrixXd R0 = M - bases[0];
  const Eigen::VectorXd r = Eigen::Map<const Eigen::VectorXd>(R0.data(), m);
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(D, Eigen::ComputeThinU | Eigen::ComputeThinV);
  ShapeAnalysis a;
  a.singular_values = svd.singularValues();
  const double keep = 1e-10 * (a.singular_values.size() ? a.singular_values(0) : 0.0);
  Eigen::VectorXd inv = Eigen::VectorXd::Zero(n - 1);
  for (int i = 0; i < n - 1; ++i)
    if (a.singular_values(i) > keep && a.singular_values(i) > 0) inv(i) = 1.0 / a.singular_values(i), ++a.rank;
  const Eigen::VectorXd y = svd.matrixV() * inv.asDiagonal() * (svd.matrixU().transpose() * r);
  a.x.resize(n);
  a.x(0) = 1.0 - y.sum();
  a.x.tail(n - 1) = y;
  a.fit = bases[0];
  for (int i = 1; i < n; ++i) a.fit += y(i - 1) * (bases[i] - bases[0]);
  const Eigen::VectorXd d = (M - a.fit).rowwise().norm();
  a.residual_rms = std::sqrt(d.squaredNorm() / static_cast<double>(d.size()));
  a.residual_max = d.maxCoeff();
  return a;
}

ShapeSpace::ShapeSpace(std::vector<TriMesh> bases, std::vector<std::string> names, ShapeMorph morph,
                       const ArapInterpolationOptions& arap)
    : morph_(morph), arap_opts_(arap) {
  check_shape_bases(bases, names);
  F_ = bases[0].F;
  for (size_t i = 0; i < bases.size(); ++i) {
    bases_.push_back(std::move(bases[i].V));
    names_.push_back(base_name(names, static_cast<int>(i)));
  }
  sources_.resize(bases_.size());
}

std::shared_ptr<const ArapSource> ShapeSpace::source(int base) {
  if (!sources_[base]) {
    try {
      sources_[base] = std::make_shared<const ArapSource>(TriMesh{bases_[base], F_, {}}, arap_opts_);
    } catch (const Error& e) {
      throw Error(names_[base] + ": " + e.what());
    }
  }
  return sources_[base];
}

// m(B_base, C, t) as rigid as possible; c_base >= 0 when C is that base (its pair is kept).
Eigen::MatrixXd ShapeSpace::arap_step(int base, const Eigen::MatrixXd& C, int c_base, double t) {
  if (c_base < 0) return ArapInterpolation(source(base), C).at(t);
  auto& pair = pairs_[{base, c_base}];
  if (!pair) pair = std::make_unique<ArapInterpolation>(source(base), C);
  return pair->at(t);
}

Eigen::MatrixXd ShapeSpace::synthesize(const Eigen::VectorXd& x) {
  check_shape_coordinates(x, size());
  if (morph_ == ShapeMorph::Linear) return synthesize_linear(bases_, x);
  const MorphChain chain = morph_chain(x);
  Eigen::MatrixXd C = bases_[chain.start];
  int c_base = chain.start;
  for (const MorphChain::Step& s : chain.steps) {
    C = arap_step(s.base, C, c_base, s.t);
    c_base = -1;
  }
  return C;
}

ShapeAnalysis ShapeSpace::analyze(const Eigen::MatrixXd& M) const { return analyze_linear(bases_, M); }

}  // namespace dfm
