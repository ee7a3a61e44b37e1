#include "core/bind/graph_cut_segmentation.h"

#include <algorithm>
#include <cmath>
#include <string>

// GCC 12 reports false maybe-uninitialized warnings inside Boost Graph's edge iterators (clang has
// no such warning).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/boykov_kolmogorov_max_flow.hpp>

#include "core/util/error.h"

namespace dfm {
namespace {

using Traits = boost::adjacency_list_traits<boost::vecS, boost::vecS, boost::directedS>;
using Edge = Traits::edge_descriptor;
using Graph = boost::adjacency_list<
    boost::vecS, boost::vecS, boost::directedS, boost::no_property,
    boost::property<boost::edge_capacity_t, double,
                    boost::property<boost::edge_residual_capacity_t, double, boost::property<boost::edge_reverse_t, Edge>>>>;

// An arc u -> v of capacity c and its reverse v -> u of capacity rc, each the other's reverse.
void add_arc(Graph& g, int u, int v, double c, double rc) {
  const Edge e = boost::add_edge(u, v, g).first, r = boost::add_edge(v, u, g).first;
  boost::put(boost::edge_capacity, g, e, c);
  boost::put(boost::edge_capacity, g, r, rc);
  boost::put(boost::edge_reverse, g, e, r);
  boost::put(boost::edge_reverse, g, r, e);
}

void check_input(const Eigen::VectorXd& w, const Eigen::MatrixXi& pairs, const Eigen::VectorXd& area,
                 const std::vector<char>& on_surface, const GraphCutOptions& opts) {
  if (pairs.rows() > 0 && pairs.cols() != 2) throw Error("graph cut: tet pairs must have two columns");
  if (area.size() != pairs.rows())
    throw Error("graph cut: " + std::to_string(area.size()) + " face areas for " + std::to_string(pairs.rows()) + " tet pairs");
  if (!on_surface.empty() && on_surface.size() != static_cast<size_t>(pairs.rows()))
    throw Error("graph cut: " + std::to_string(on_surface.size()) + " surface flags for " + std::to_string(pairs.rows()) + " tet pairs");
  if (pairs.size() > 0 && (pairs.minCoeff() < 0 || pairs.maxCoeff() >= w.size()))
    throw Error("graph cut: a tet pair refers to a tet out of range (" + std::to_string(w.size()) + " tets)");
  if (!w.allFinite()) throw Error("graph cut: a winding number is not finite");
  if (!(opts.gamma >= 0) || !(opts.sigma > 0) || !(opts.surface_factor >= 0))
    throw Error("graph cut: gamma and surface_factor must be >= 0 and sigma > 0");
}

// Medians, not means: the few huge tets in a padded box's corners would dominate a mean.
double median(const Eigen::VectorXd& x) {
  if (x.size() == 0) return 0;
  std::vector<double> v(x.data(), x.data() + x.size());
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

}  // namespace

std::vector<char> threshold_segmentation(const Eigen::VectorXd& w) {
  std::vector<char> in(w.size());
  for (Eigen::Index t = 0; t < w.size(); ++t) in[t] = w(t) > 0.5;
  return in;
}

std::vector<char> graph_cut_segmentation(const Eigen::VectorXd& w, const Eigen::VectorXd& volume,
                                         const Eigen::MatrixXi& pairs, const Eigen::VectorXd& area,
                                         const std::vector<char>& on_surface, const GraphCutOptions& opts) {
  check_input(w, pairs, area, on_surface, opts);
  if (volume.size() != 0 && volume.size() != w.size())
    throw Error("graph cut: " + std::to_string(volume.size()) + " tet volumes for " + std::to_string(w.size()) + " tets");
  if (volume.size() && !(volume.minCoeff() >= 0 && volume.allFinite())) throw Error("graph cut: a tet volume is negative or not finite");
  const int n = static_cast<int>(w.size());
  if (n == 0) return {};
  const double typical_area = median(area);
  const double typical_volume = median(volume);
  if (opts.gamma == 0 || !(typical_area > 0)) return threshold_segmentation(w);

  // Vertices: tets, then source (inside) and sink (outside). Kolmogorov & Zabih 2004: labelling a tet
  // outside cuts its source arc, inside its sink arc; only the difference of the two data costs
  // matters, so each tet gets one terminal arc.
  const int source = n, sink = n + 1;
  Graph g(n + 2);
  for (int t = 0; t < n; ++t) {
    // w(e_i) is an integral average (8.5.1): weighted by volume, the sum discretizes the integral.
    const double scale = typical_volume > 0 ? volume(t) / typical_volume : 1.0;
    const double out_cost = scale * std::max(w(t), 0.0), in_cost = scale * std::max(1.0 - w(t), 0.0);  // Eq. 8.9
    if (out_cost > in_cost) add_arc(g, source, t, out_cost - in_cost, 0);
    else if (in_cost > out_cost) add_arc(g, t, sink, in_cost - out_cost, 0);
  }
  const double inv_two_sigma2 = 1.0 / (2 * opts.sigma * opts.sigma);
  for (int a = 0; a < pairs.rows(); ++a) {  // Eq. 8.10, each pair once (the 1/2 in Eq. 8.8)
    const int i = pairs(a, 0), j = pairs(a, 1);
    const double dw = w(i) - w(j);
    double c = opts.gamma * area(a) / typical_area * std::exp(-dw * dw * inv_two_sigma2);
    if (!on_surface.empty() && on_surface[a]) c *= opts.surface_factor;
    if (c > 0 && i != j) add_arc(g, i, j, c, c);
  }

  std::vector<boost::default_color_type> color(n + 2);
  std::vector<Edge> pred(n + 2);
  std::vector<long> dist(n + 2);
  const auto index = boost::get(boost::vertex_index, g);
  boost::boykov_kolmogorov_max_flow(g, boost::get(boost::edge_capacity, g), boost::get(boost::edge_residual_capacity, g),
                                    boost::get(boost::edge_reverse, g),
                                    boost::make_iterator_property_map(pred.begin(), index),
                                    boost::make_iterator_property_map(color.begin(), index),
                                    boost::make_iterator_property_map(dist.begin(), index), index, source, sink);
  // Black: in the source's tree after the flow, i.e. on the inside of the minimum cut.
  std::vector<char> in(n);
  for (int t = 0; t < n; ++t) in[t] = color[t] == boost::color_traits<boost::default_color_type>::black();
  return in;
}

}  // namespace dfm
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
