#pragma once
// Inside/outside labels for the tets of a winding-number volume by minimizing Jacobson 2013's energy
// (section 8.5.1, Eqs. 8.8-8.10) with a max-flow min-cut (Boost Graph's Boykov-Kolmogorov), instead
// of the plain threshold w > 1/2 (Eq. 8.7), which ignores neighbours and leaves splinters and holes
// near ambiguous input (open boundaries, flipped or duplicated facets).
#include <vector>

#include <Eigen/Core>

namespace dfm {

// Defaults chosen on messy copies of closed meshes (bench/bench_segmentation prints the misclassified
// tets of threshold and cut; tests/test_graph_cut.cpp); gamma 1-4 and sigma 0.3-0.4 all do well.
// Unweighted data (Eq. 8.8 as printed) misclassifies more on graded meshes and lets big tets near
// w = 1/2 follow their large faces; mean-normalized volumes let the padded box's huge tets dominate.
struct GraphCutOptions {
  // gamma in Eq. 8.8: smoothness against the data term. Face areas are divided by their median and tet
  // volumes by theirs, so the balance does not depend on the model's scale. 0 is the threshold.
  double gamma = 2.0;
  // sigma in Eq. 8.10 (read as a_ij exp(-dw^2 / (2 sigma^2)), Boykov & Funka-Lea 2006): the
  // winding-number jump across a face that makes cutting it cheap; a jump of 1 costs exp(-3.1) at 0.4.
  double sigma = 0.4;
  // Factor on the smoothness of faces that are input facets (the on-surface indicator): 0 makes the
  // input surface free to cut along, so thin parts bounded by facets are never shaved off for the sake
  // of a smaller boundary.
  double surface_factor = 0.0;
  bool operator==(const GraphCutOptions& o) const {
    return gamma == o.gamma && sigma == o.sigma && surface_factor == o.surface_factor;
  }
};

// w: #T winding numbers (integral averages per tet). volume: #T tet volumes weighting the data term
// (Eq. 8.9 times volume / median volume), or empty for Eq. 8.8 as printed (every tet counts once; on
// graded meshes this lets big tets near w = 1/2 follow their neighbours' larger faces). pairs: #A x 2
// tets sharing a face, area: #A face areas, on_surface: #A flags (empty: none). Returns #T labels,
// 1 = inside. Throws dfm::Error on mismatched sizes, a tet index out of range or a bad value.
std::vector<char> graph_cut_segmentation(const Eigen::VectorXd& w, const Eigen::VectorXd& volume,
                                         const Eigen::MatrixXi& pairs, const Eigen::VectorXd& area,
                                         const std::vector<char>& on_surface, const GraphCutOptions& opts = {});

// Eq. 8.7: 1 where w > 1/2.
std::vector<char> threshold_segmentation(const Eigen::VectorXd& w);

}  // namespace dfm
