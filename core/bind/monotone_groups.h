#pragma once
// Active sets of the pairwise monotonicity constraints (monotone_constraints.h), shared by the per-handle
// QP (monotone_qp.h) and the joint one (monotone_joint.h): the groups of nodes an active set makes equal,
// and the multipliers of its spanning forest from a gradient.
#include <vector>

#include <Eigen/Core>

#include "core/bind/monotone_constraints.h"

namespace dfm {

// The groups an active set makes: free variables joined by active constraints share one unknown, or
// the fixed value their group reaches. tree[c]: c joined two groups (a spanning forest of the active set).
struct MonotoneGroups {
  std::vector<int> root;     // per node (free and fixed): its group's union-find root
  std::vector<int> unknown;  // per free variable: reduced index, or -1 when fixed
  std::vector<double> value; // per free variable with unknown -1: its fixed value
  std::vector<char> tree;
  int count = 0;
  int conflicts = 0;  // active constraints that would join two different fixed values (left out)
};

MonotoneGroups make_monotone_groups(int nf, const MonotoneProblem& p, const std::vector<char>& active);

// Multipliers of the spanning-forest constraints from the gradient r (stationarity
// r_i = sum_{c: upper = i} lambda_c - sum_{c: lower = i} lambda_c); other constraints get 0.
std::vector<double> monotone_multipliers(const MonotoneProblem& p, const MonotoneGroups& gr, const Eigen::VectorXd& r);

}  // namespace dfm
