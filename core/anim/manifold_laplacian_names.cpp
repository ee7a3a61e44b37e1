// The Laplacian weights' names (manifold_laplacian.h), apart from the Laplacian itself: scene files
// read and write them, and the scene reader's fuzz target links this without the solver.
#include <string>

#include "core/anim/manifold_laplacian.h"
#include "core/util/error.h"

namespace dfm {

LaplacianWeights parse_laplacian_weights(const std::string& name) {
  if (name == "equal") return LaplacianWeights::Equal;
  if (name == "reciprocal") return LaplacianWeights::Reciprocal;
  if (name == "primal-boundary") return LaplacianWeights::PrimalBoundary;
  if (name == "dual") return LaplacianWeights::Dual;
  throw Error("unknown Laplacian weights '" + name + "' (equal, reciprocal, primal-boundary, dual)");
}

const char* laplacian_weights_name(LaplacianWeights w) {
  switch (w) {
    case LaplacianWeights::Equal: return "equal";
    case LaplacianWeights::PrimalBoundary: return "primal-boundary";
    case LaplacianWeights::Dual: return "dual";
    default: return "reciprocal";
  }
}

}  // namespace dfm
