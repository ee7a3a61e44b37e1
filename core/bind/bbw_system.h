#pragma once
// The data every bounded weight solve shares (Jacobson 2013, 4.2): the energy Q restricted to the free
// vertices, each handle's linear term, and a fill-reducing renumbering of the free variables.
#include <functional>

#include <Eigen/Core>
#include <Eigen/Sparse>

namespace dfm {

struct FreeSystem {
  Eigen::SparseMatrix<double> Qff;  // Q on the free vertices
  Eigen::MatrixXd G;                // #free x #handles: g_j = Q_fb bc_j
  Eigen::VectorXi vertex;           // variable k -> its mesh vertex
  long factor_nonzeros = 0;         // of Q_ff's Cholesky factor (after order_free_system)
};

// Splits Q (#V x #V) into the free part and the linear terms of the constraints w(b) = bc.
FreeSystem split_free_fixed(Eigen::SparseMatrix<double> Q, const Eigen::VectorXi& b, const Eigen::MatrixXd& bc);

// Renumbers the variables in a nested-dissection order (a vertex's neighbours then sit close to it in
// memory, which makes the Gauss-Seidel sweeps and products with Q_ff faster than in TetGen's order,
// and every face is already in elimination order). With bound_free_start it also factorizes Q_ff once
// and returns the bound-free solutions -Q_ff^-1 G (renumbered), which start the bounded solves (often
// nearly feasible); else an empty matrix. ordered(): called between the ordering and the factorization.
Eigen::MatrixXd order_free_system(FreeSystem& sys, bool bound_free_start, int threads,
                                  const std::function<void()>& ordered = {});

}  // namespace dfm
