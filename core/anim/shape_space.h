#pragma once
// Shape spaces from morphing (Alexa 2002, ch. 5). n base shapes of one connectivity span a space; an
// element is written with barycentric coordinates x: n weights summing to 1, one per base (Eq. 5.17,
// 5.18), so base i is the unit vector e_i.
//
// Synthesis (5.5.1) is Eq. 5.31's chain of n - 1 pairwise morphs in the bases' order (the order is a
// parameter of a non-linear space): C_{n-1} = B_{n-1}, C_k = m(B_k, C_{k+1}, S_{k+1} / S_k) with the
// partial sums S_k = x_k + ... + x_{n-1}, and C_0 is the result. The chain starts at the last base with
// a nonzero weight (the later C_k are 0/0 and unused) and copies C where t is exactly 1 (x_k = 0), so
// at e_i the result is B_i bit for bit. m is the linear blend (a vector space, Eq. 5.36) or the
// as-rigid-as-possible interpolation (4.4, core/anim/arap_interpolation.h). The chain depends on x only
// through ratios of partial sums, so it synthesizes x / sum(x).
//
// Analysis (5.5.2-5.5.3): in the linear space, the coordinates of a mesh M are those of its
// least-squares projection onto the affine span of the bases (vertex positions as the norm's vector).
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "core/anim/arap_interpolation.h"
#include "core/mesh/mesh.h"

namespace dfm {

enum class ShapeMorph { Linear, Arap };
// "linear" or "arap"; dfm::Error otherwise.
ShapeMorph parse_shape_morph(const std::string& name);
const char* shape_morph_name(ShapeMorph m);

// n >= 2 bases, every one with bases[0]'s vertex count and triangles, finite positions. `names` (one
// per base, or empty) name the bases in the messages. Throws dfm::Error.
void check_shape_bases(const std::vector<TriMesh>& bases, const std::vector<std::string>& names = {});

// n coordinates, finite, summing to 1 within 1e-6. Throws dfm::Error.
void check_shape_coordinates(const Eigen::VectorXd& x, int n);

// Eq. 5.31 for coordinates x: start from B_start, then C = m(B_base, C, t) for each step in order
// (bases descending). Steps with t == 1 (a zero weight) are left out. A partial sum S_k (k below the
// last nonzero weight) within 1e-9 sum |x_i| of 0 makes t undefined for this order: dfm::Error.
struct MorphChain {
  struct Step {
    int base = 0;
    double t = 0;
  };
  int start = 0;
  std::vector<Step> steps;
};
MorphChain morph_chain(const Eigen::VectorXd& x);

// The chain with the linear morph: close to sum x_i B_i (Eq. 5.36), exactly B_i at e_i.
Eigen::MatrixXd synthesize_linear(const std::vector<Eigen::MatrixXd>& bases, const Eigen::VectorXd& x);

struct ShapeAnalysis {
  Eigen::VectorXd x;                // n coordinates summing to 1
  Eigen::MatrixXd fit;              // sum x_i B_i: the nearest element of the space
  double residual_rms = 0;          // root mean square of the vertex distances from M to `fit`
  double residual_max = 0;          // the largest of them
  Eigen::VectorXd singular_values;  // of [B_1 - B_0 ... B_{n-1} - B_0], descending
  int rank = 0;                     // singular values above 1e-10 times the largest
  // 5.5.3's quality measure: smallest over largest singular value (0: the bases are linearly dependent
  // and the coordinates are the least-squares solution of least norm).
  double quality() const;
};

// Least-squares coordinates of M in the linear space of the bases, sum-to-one by construction
// (x_0 = 1 - x_1 - ... - x_{n-1}); an SVD solves it, zero singular values inverted as 0 (5.5.3).
ShapeAnalysis analyze_linear(const std::vector<Eigen::MatrixXd>& bases, const Eigen::MatrixXd& M);

// A shape space of fixed bases and morph, for repeated synthesis (a drag): the ARAP setups are built
// on first use and kept (one per base as a morph's source; one per pair of bases for the chain's
// first morph, whose target is a base).
class ShapeSpace {
 public:
  // Checks the bases (check_shape_bases). `names` label the bases in messages.
  ShapeSpace(std::vector<TriMesh> bases, std::vector<std::string> names, ShapeMorph morph,
             const ArapInterpolationOptions& arap = {});
  int size() const { return static_cast<int>(bases_.size()); }
  ShapeMorph morph() const { return morph_; }
  const Eigen::MatrixXi& faces() const { return F_; }
  const std::vector<Eigen::MatrixXd>& bases() const { return bases_; }
  const std::vector<std::string>& names() const { return names_; }
  // The vertices at coordinates x (check_shape_coordinates). ARAP errors (TetGen on a base) name the base.
  Eigen::MatrixXd synthesize(const Eigen::VectorXd& x);
  // analyze_linear on the bases (the linear space, whatever the morph). M: one row per vertex.
  ShapeAnalysis analyze(const Eigen::MatrixXd& M) const;

 private:
  std::shared_ptr<const ArapSource> source(int base);
  Eigen::MatrixXd arap_step(int base, const Eigen::MatrixXd& C, int c_base, double t);

  Eigen::MatrixXi F_;
  std::vector<Eigen::MatrixXd> bases_;
  std::vector<std::string> names_;
  ShapeMorph morph_;
  ArapInterpolationOptions arap_opts_;
  std::vector<std::shared_ptr<const ArapSource>> sources_;
  std::map<std::pair<int, int>, std::unique_ptr<ArapInterpolation>> pairs_;
};

}  // namespace dfm
