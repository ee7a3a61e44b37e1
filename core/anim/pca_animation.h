#pragma once
// Animations from base shapes (Alexa 2003, ch. 7.2): a sequence of frames with one connectivity becomes
// a mean shape plus k base shapes, after each frame's rigid motion is taken out.
//
//   aligned_i = R_i^T (frame_i - t_i)                 rigid motion removed (7.2, "normalization")
//   X         = [vec(aligned_0 - mean) ... ]          the centred, aligned frame matrix, 3#V x #frames
//   X         = U S W^T                               thin SVD (Eq. 7.7)
//   frame_i  ~= R_i (mean + sum_j c_ij B_j) + t_i     B_j = column j of U (j < k), c_ij = B_j . X_i
//
// By Eckart-Young the k leading singular vectors give the smallest Frobenius error of any rank-k
// approximation of X: the total error is sqrt(sum of the discarded S_j^2), and the projection
// coefficients make each frame's error the smallest its k bases allow.
// Vectors of 3#V entries are vertex-major: entry 3v + c is vertex v's coordinate c (x, y, z).
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace dfm {

// Where a frame sits in the world: frame = rotation * aligned + translation (row by row).
struct RigidMotion {
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();  // unit
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
};

// The compressed animation (what a .pca file holds, see pca_file.h).
struct PcaAnimation {
  Eigen::MatrixXi F;                  // #F x 3, shared by every frame
  Eigen::MatrixXd mean;               // #V x 3, aligned space (centroid at the origin)
  Eigen::MatrixXd bases;              // 3#V x k, orthonormal columns, in decreasing importance
  Eigen::MatrixXd coefficients;       // #frames x k
  std::vector<RigidMotion> motion;    // #frames
  std::vector<double> times;          // #frames, strictly increasing (seconds)
  int num_vertices() const { return static_cast<int>(mean.rows()); }
  int num_frames() const { return static_cast<int>(coefficients.rows()); }
  int num_bases() const { return static_cast<int>(bases.cols()); }
};

// Every frame aligned to frame 0 without scale or reflection: t_i is frame i's vertex centroid (the
// best translation) and R_i the rotation taking centred frame 0 closest to centred frame i (Kabsch),
// so aligned_i is the rigid copy of frame i nearest to centred frame 0.
struct AlignedFrames {
  std::vector<Eigen::MatrixXd> aligned;  // #V x 3 each, centroid at the origin; aligned_0 = centred frame 0
  std::vector<RigidMotion> motion;
};
// Throws dfm::Error for no frames, an empty frame, frames that differ in size or non-finite values.
AlignedFrames align_frames(const std::vector<Eigen::MatrixXd>& frames);

// The whole decomposition, computed once and cut to any k by pca_animation().
struct PcaDecomposition {
  Eigen::MatrixXd mean;                 // #V x 3
  Eigen::MatrixXd centred;              // X: 3#V x #frames
  Eigen::MatrixXd U;                    // 3#V x r left singular vectors, r = min(3#V, #frames)
  Eigen::VectorXd singular_values;      // r, decreasing
  std::vector<RigidMotion> motion;      // #frames
  double bbox_diagonal = 0.0;           // of frame 0, the unit of the relative errors
  int num_frames() const { return static_cast<int>(centred.cols()); }
  int max_bases() const { return static_cast<int>(U.cols()); }
};
// Aligns (align_frames), centres and takes the thin SVD of X (Householder QR, then BDCSVD of the square
// factor: backward stable, so every kept singular vector is accurate to rounding relative to S_1; the
// eigenvectors of the small Gram matrix X^T X are about 3 times faster but lose the bases whose S_j is
// below sqrt(eps) S_1: bench_compress measures both).
PcaDecomposition decompose_frames(const std::vector<Eigen::MatrixXd>& frames);

// The first k bases with each frame's projection coefficients. F: the shared triangles; times: one
// per frame, strictly increasing. Throws dfm::Error for k outside [0, max_bases()] or bad times/F.
PcaAnimation pca_animation(const PcaDecomposition& d, int k, const Eigen::MatrixXi& F,
                           const std::vector<double>& times);

// Frame i in aligned space (mean + sum_j c_ij B_j) and in the world (its rigid motion put back).
Eigen::MatrixXd pca_aligned_frame(const PcaAnimation& a, int i);
Eigen::MatrixXd pca_frame(const PcaAnimation& a, int i);

// Reconstruction error per frame, measured in aligned space (equal to the world-space error: the
// rigid motion is stored, not approximated).
struct PcaErrors {
  std::vector<double> frobenius;   // ||aligned_i - reconstruction_i||_F (the square root of the sum
                                   // of squared vertex distances)
  std::vector<double> max_vertex;  // the largest vertex distance in frame i
  double total = 0.0;              // sqrt(sum_i frobenius_i^2) = ||X - B B^T X||_F
  int num_vertices = 0;
  double bbox_diagonal = 0.0;      // of frame 0
  // RMS vertex distance of frame i as a fraction of the bounding-box diagonal.
  double rms_relative(int i) const;
};
PcaErrors pca_errors(const PcaDecomposition& d, const PcaAnimation& a);

// Evenly spaced times i / fps. Throws dfm::Error unless fps > 0.
std::vector<double> frame_times(int frames, double fps);

}  // namespace dfm
