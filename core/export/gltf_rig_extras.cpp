#include "core/export/gltf_rig_extras.h"

#include <cmath>

#include <nlohmann/json.hpp>

#include "core/util/error.h"

namespace dfm {

using json = nlohmann::json;

namespace {

template <class Matrix>
json rows(const Matrix& M) {
  json a = json::array();
  for (Eigen::Index i = 0; i < M.rows(); ++i) {
    json r = json::array();
    for (Eigen::Index j = 0; j < M.cols(); ++j) r.push_back(M(i, j));
    a.push_back(r);
  }
  return a;
}

// Reads with the context of the text's owner: every problem is an Error naming it.
struct Reader {
  std::string what;

  [[noreturn]] void fail(const std::string& problem) const { throw Error(what + ": deform_rig extras: " + problem); }
  const json& at(const json& o, const char* key) const {
    if (!o.is_object() || !o.contains(key)) fail(std::string("missing '") + key + "'");
    return o[key];
  }
  std::string text(const json& o, const char* key) const {
    const json& v = at(o, key);
    if (!v.is_string()) fail(std::string("'") + key + "' is not a string");
    return v.get<std::string>();
  }
  const json& list(const json& o, const char* key) const {
    const json& v = at(o, key);
    if (!v.is_array()) fail(std::string("'") + key + "' is not an array");
    return v;
  }
  Eigen::MatrixXd reals(const json& a, int cols, const char* name) const {
    Eigen::MatrixXd M(static_cast<Eigen::Index>(a.size()), cols);
    for (size_t i = 0; i < a.size(); ++i) {
      if (!a[i].is_array() || a[i].size() != static_cast<size_t>(cols)) fail(std::string("a row of '") + name + "' is not " + std::to_string(cols) + " numbers");
      for (int j = 0; j < cols; ++j) {
        if (!a[i][j].is_number() || !std::isfinite(a[i][j].get<double>())) fail(std::string("'") + name + "' holds a value that is not a finite number");
        M(static_cast<Eigen::Index>(i), j) = a[i][j].get<double>();
      }
    }
    return M;
  }
  Eigen::MatrixXi indices(const json& a, int cols, long long below, const char* name) const {
    Eigen::MatrixXi M(static_cast<Eigen::Index>(a.size()), cols);
    for (size_t i = 0; i < a.size(); ++i) {
      if (!a[i].is_array() || a[i].size() != static_cast<size_t>(cols)) fail(std::string("a row of '") + name + "' is not " + std::to_string(cols) + " indices");
      for (int j = 0; j < cols; ++j) {
        if (!a[i][j].is_number_integer() || a[i][j].get<long long>() < 0 || a[i][j].get<long long>() >= below)
          fail(std::string("'") + name + "' holds an index out of range");
        M(static_cast<Eigen::Index>(i), j) = a[i][j].get<int>();
      }
    }
    return M;
  }
};

}  // namespace

std::string rig_extras_json(const Rig& rig) {
  json j;
  j["points"] = json::array();
  for (const PointHandle& p : rig.points) j["points"].push_back({{"name", p.name}, {"position", {p.position.x(), p.position.y(), p.position.z()}}});
  j["joints"] = rows(rig.skeleton.joints);
  j["bones"] = json::array();
  for (const Bone& b : rig.skeleton.bones) j["bones"].push_back({{"name", b.name}, {"a", b.a}, {"b", b.b}});
  j["cages"] = json::array();
  for (const Cage& c : rig.cages) j["cages"].push_back({{"name", c.name}, {"V", rows(c.mesh.V)}, {"F", rows(c.mesh.F)}, {"edges", rows(c.edges)}});
  j["regions"] = json::array();
  for (const Region& r : rig.regions) j["regions"].push_back({{"name", r.name}, {"vertices", r.vertices}});
  j["pseudo_edges"] = json::array();
  for (auto [a, b] : rig.pseudo_edges) j["pseudo_edges"].push_back({a, b});
  return j.dump();
}

Rig rig_from_extras_json(const std::string& text, int num_surface_vertices, const std::string& what) {
  const Reader R{what};
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {
    R.fail(std::string("not JSON: ") + e.what());
  }
  Rig rig;
  for (const json& p : R.list(j, "points")) {
    const Eigen::MatrixXd x = R.reals(json::array({R.at(p, "position")}), 3, "position");
    rig.points.push_back({x.row(0).transpose(), R.text(p, "name")});
  }
  rig.skeleton.joints = R.reals(R.list(j, "joints"), 3, "joints");
  for (const json& b : R.list(j, "bones")) {
    const Eigen::MatrixXi ab = R.indices(json::array({{R.at(b, "a"), R.at(b, "b")}}), 2, rig.skeleton.num_joints(), "bones");
    Bone bone;
    bone.a = ab(0, 0), bone.b = ab(0, 1), bone.name = R.text(b, "name");
    if (bone.a == bone.b) R.fail("a bone joins a joint to itself");
    rig.skeleton.bones.push_back(bone);
  }
  try {
    compute_bone_parents(rig.skeleton);
  } catch (const Error& e) {
    R.fail(e.what());
  }
  for (const json& c : R.list(j, "cages")) {
    Cage cage;
    cage.name = R.text(c, "name");
    cage.mesh.V = R.reals(R.list(c, "V"), 3, "V");
    cage.mesh.F = R.indices(R.list(c, "F"), 3, cage.mesh.V.rows(), "F");
    cage.edges = R.indices(R.list(c, "edges"), 2, cage.mesh.V.rows(), "edges");
    rig.cages.push_back(std::move(cage));
  }
  for (const json& r : R.list(j, "regions")) {
    Region region;
    region.name = R.text(r, "name");
    const json& v = R.list(r, "vertices");
    for (const json& i : v) {
      if (!i.is_number_integer() || i.get<long long>() < 0 || i.get<long long>() >= num_surface_vertices)
        R.fail("a region's vertex is out of range");
      region.vertices.push_back(i.get<int>());
    }
    rig.regions.push_back(std::move(region));
  }
  const Eigen::MatrixXi pe = R.indices(R.list(j, "pseudo_edges"), 2, static_cast<long long>(rig.points.size()), "pseudo_edges");
  for (Eigen::Index i = 0; i < pe.rows(); ++i) rig.pseudo_edges.emplace_back(pe(i, 0), pe(i, 1));
  return rig;
}

}  // namespace dfm
