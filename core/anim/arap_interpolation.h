#pragma once
// As-rigid-as-possible shape interpolation (Alexa 2002, 4.4.3-4.4.5), generalized to tetrahedra:
// the first key's interior is tetrahedralized (TetGen, as the bind does), the second key is carried
// through the same tets (its interior vertices solved as rigid as possible to the first, 4.4.1's
// compatible dissection), and each tet's affine map A = R S interpolates as R(t) ((1 - t) I + t S)
// (4.1.1), R(t) turning by t times its angle, the angles chosen consistently across neighbouring tets
// so a 270 degree twist is not taken as -90. The vertex paths minimize Eq. 4.24 (volume-weighted):
// one factorization per first key (Eq. 4.27; ArapSource), one back substitution per time. Keys are hit
// exactly.
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCholesky>

#include "core/mesh/mesh.h"

namespace dfm {

struct ArapInterpolationOptions {
  std::string tetgen_switches = "pq1.414Y";  // Y: the surface stays the key's own
  int interior_iterations = 30;              // local-global iterations carrying the second key's interior
  // 4.4.6's symmetric form (Eq. 4.28): the energies from both keys blended, (1 - t) E-> + t E<-, so tets
  // of very different size in the two keys weigh alike from either side. Costs one factorization per time.
  bool symmetric = false;
};

struct ArapInterpolationStats {
  int tets = 0, tet_vertices = 0;
  double tetrahedralize_seconds = 0, interior_seconds = 0, factor_seconds = 0;
};

// The first key's half of the setup, shared by every interpolation from it (a shape space's chain of
// morphs, ch. 5, morphs one base to many targets): its tets, hat gradients, volumes and the two
// factorizations (interior carrying and Eq. 4.27's vertex paths), which depend on the first key only.
class ArapSource {
 public:
  // k0: a closed surface. Throws dfm::Error when TetGen fails on it.
  explicit ArapSource(const TriMesh& k0, const ArapInterpolationOptions& opts = {});
  int surface_vertices() const { return static_cast<int>(key_.rows()); }
  const ArapInterpolationStats& stats() const { return stats_; }  // interior_seconds: 0

 private:
  friend class ArapInterpolation;
  Eigen::MatrixXd key_;
  int interior_iterations_ = 30;
  TetMesh rest_;                       // the first key's tets
  Eigen::VectorXd vol_;                // its tet volumes
  Eigen::VectorXi surface_to_tet_;     // k0 vertex -> tet vertex
  std::vector<Eigen::Matrix<double, 3, 4>> grad_;  // per tet: hat-function gradients
  std::vector<int> interior_;          // tet vertices not on the surface
  Eigen::SparseMatrix<double> Kib_;    // stiffness rows of the interior, all columns
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> inner_;   // interior block
  Eigen::SparseMatrix<double> K_fixed_col_;  // stiffness columns of the fixed vertex, free rows
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver_;  // all but the fixed vertex
  std::vector<int> free_index_;  // tet vertex -> row among the free ones (-1 for the fixed vertex)
  int fixed_ = 0;
  bool symmetric_ = false;
  Eigen::SparseMatrix<double> Kff_;  // K without the fixed vertex (symmetric form only)
  ArapInterpolationStats stats_;
};

class ArapInterpolation {
 public:
  // k0: a closed surface; k1: the second key's vertices on k0's triangles (same count and order).
  // Throws dfm::Error on a count mismatch or when TetGen fails on k0.
  ArapInterpolation(const TriMesh& k0, const Eigen::MatrixXd& k1, const ArapInterpolationOptions& opts = {});
  // The same with k0's half of the setup built before (the same result as building it here).
  ArapInterpolation(std::shared_ptr<const ArapSource> source, const Eigen::MatrixXd& k1);
  // The surface vertices at t (t = 0 and 1 give the keys; other t extrapolate).
  Eigen::MatrixXd at(double t) const;
  // The source's stages (as measured when it was built) and this pair's interior carrying.
  const ArapInterpolationStats& stats() const { return stats_; }

 private:
  void carry(const Eigen::MatrixXd& k1);  // target_, angle_, stretch_ from the second key
  void setup_reverse();                   // the symmetric form's energy from the second key
  // Eq. 4.22's target of tet k at t, and for the symmetric form the reverse one (second key -> time t).
  Eigen::Matrix3d forward_target(int k, double t) const;
  Eigen::Matrix3d reverse_target(int k, double t) const;
  Eigen::MatrixXd surface_of(const Eigen::MatrixXd& X_free, const Eigen::RowVector3d& p_fixed) const;
  std::shared_ptr<const ArapSource> src_;
  Eigen::MatrixXd key1_;
  Eigen::MatrixXd target_;             // tet vertices carried to the second key
  std::vector<Eigen::Vector3d> angle_;  // per tet: rotation vector of R (consistent branch)
  std::vector<Eigen::Matrix3d> stretch_;  // per tet: S
  // Symmetric form: the second key's tets (hat gradients, volumes) and its K without the fixed vertex.
  std::vector<Eigen::Matrix<double, 3, 4>> grad1_;
  Eigen::VectorXd vol1_;
  Eigen::SparseMatrix<double> K1ff_, K1_fixed_col_;
  ArapInterpolationStats stats_;
};

// (1 - t) a + t b, the linear in-between (`--method linear`).
Eigen::MatrixXd linear_interpolation(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double t);

}  // namespace dfm
