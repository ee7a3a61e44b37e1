#include "core/rig/rig.h"

#include <algorithm>
#include <cctype>
#include <functional>

#include "core/util/error.h"

namespace dfm {

int num_point_handles(const Rig& rig) { return static_cast<int>(rig.points.size()); }

int num_cage_vertices(const Rig& rig) {
  int n = 0;
  for (const Cage& c : rig.cages) n += c.mesh.num_vertices();
  return n;
}

int num_handles(const Rig& rig) {
  return num_point_handles(rig) + rig.skeleton.num_bones() + num_cage_vertices(rig) +
         static_cast<int>(rig.regions.size());
}

HandleRef handle_ref(const Rig& rig, int h) {
  if (h < 0 || h >= num_handles(rig)) throw Error("handle index " + std::to_string(h) + " out of range");
  if (h < num_point_handles(rig)) return {HandleKind::Point, h};
  h -= num_point_handles(rig);
  if (h < rig.skeleton.num_bones()) return {HandleKind::Bone, h};
  h -= rig.skeleton.num_bones();
  for (int c = 0; c < static_cast<int>(rig.cages.size()); ++c) {
    int n = rig.cages[c].mesh.num_vertices();
    if (h < n) return {HandleKind::CageVertex, h, c};
    h -= n;
  }
  return {HandleKind::Region, h};
}

int handle_index(const Rig& rig, const HandleRef& r) {
  switch (r.kind) {
    case HandleKind::Point: return r.index;
    case HandleKind::Bone: return num_point_handles(rig) + r.index;
    case HandleKind::CageVertex: {
      int base = num_point_handles(rig) + rig.skeleton.num_bones();
      for (int c = 0; c < r.cage; ++c) base += rig.cages[c].mesh.num_vertices();
      return base + r.index;
    }
    case HandleKind::Region:
      return num_point_handles(rig) + rig.skeleton.num_bones() + num_cage_vertices(rig) + r.index;
  }
  return -1;
}

const char* handle_kind_name(HandleKind k) {
  switch (k) {
    case HandleKind::Point: return "point";
    case HandleKind::Bone: return "bone";
    case HandleKind::CageVertex: return "cage vertex";
    case HandleKind::Region: return "region";
  }
  return "?";
}

std::string handle_name(const Rig& rig, int h) {
  HandleRef r = handle_ref(rig, h);
  std::string given;
  switch (r.kind) {
    case HandleKind::Point: given = rig.points[r.index].name; break;
    case HandleKind::Bone: given = rig.skeleton.bones[r.index].name; break;
    case HandleKind::CageVertex:
      given = (rig.cages[r.cage].name.empty() ? "cage " + std::to_string(r.cage) : rig.cages[r.cage].name) +
              " vertex " + std::to_string(r.index);
      break;
    case HandleKind::Region: given = rig.regions[r.index].name; break;
  }
  if (!given.empty()) return given;
  return std::string(handle_kind_name(r.kind)) + " " + std::to_string(r.index);
}

namespace {

// Levenshtein distance, case-insensitive (names are short: the full table is fine).
int edit_distance(const std::string& a, const std::string& b) {
  std::vector<int> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = static_cast<int>(j);
  for (size_t i = 1; i <= a.size(); ++i) {
    int diag = row[0];
    row[0] = static_cast<int>(i);
    for (size_t j = 1; j <= b.size(); ++j) {
      const int up = row[j];
      const bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) == std::tolower(static_cast<unsigned char>(b[j - 1]));
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (same ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

bool is_integer(const std::string& w) {
  size_t i = !w.empty() && (w[0] == '-' || w[0] == '+') ? 1 : 0;
  if (i == w.size() || w.size() - i > 9) return false;
  for (; i < w.size(); ++i)
    if (!std::isdigit(static_cast<unsigned char>(w[i]))) return false;
  return true;
}

}  // namespace

int find_handle(const Rig& rig, const std::string& word) {
  const int n = num_handles(rig);
  if (is_integer(word)) {
    const int h = std::stoi(word);
    if (h < 0 || h >= n)
      throw Error("no handle " + word + " (the rig has " + std::to_string(n) + " handle" + (n == 1 ? "" : "s") +
                  (n > 0 ? ": 0.." + std::to_string(n - 1) : "") + ")");
    return h;
  }
  std::vector<int> exact;
  std::vector<std::pair<int, std::string>> close;  // (distance, name)
  const int reach = std::max<int>(2, static_cast<int>(word.size()) / 3);
  for (int h = 0; h < n; ++h) {
    const std::string name = handle_name(rig, h);
    if (name == word) exact.push_back(h);
    const int d = edit_distance(word, name);
    if (d <= reach) close.emplace_back(d, name + " (" + std::to_string(h) + ")");
  }
  if (exact.size() == 1) return exact[0];
  if (exact.size() > 1) {
    std::string which;
    for (int h : exact) which += (which.empty() ? "" : ", ") + std::to_string(h);
    throw Error("handle name '" + word + "' is shared by handles " + which + ": use the number");
  }
  std::stable_sort(close.begin(), close.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::string list;
  for (size_t i = 0; i < close.size() && i < 5; ++i) list += (i ? ", " : "") + close[i].second;
  throw Error("no handle named '" + word + "'" + (list.empty() ? " (and none close; handles are also numbered 0.." +
                                                                  std::to_string(std::max(0, n - 1)) + ")"
                                                             : "; close: " + list));
}

void compute_bone_parents(Skeleton& s) {
  for (Bone& b : s.bones) {
    b.parent = -1;
    for (int k = 0; k < s.num_bones(); ++k)
      if (s.bones[k].b == b.a && &s.bones[k] != &b) {
        b.parent = k;
        break;
      }
  }
  bones_topological_order(s);  // throws on cycles
}

std::vector<int> bones_topological_order(const Skeleton& s) {
  const int n = s.num_bones();
  std::vector<int> order, state(n, 0);  // 0 new, 1 visiting, 2 done
  std::function<void(int)> visit = [&](int i) {
    if (state[i] == 2) return;
    if (state[i] == 1) throw Error("skeleton has a cycle of bones through bone " + std::to_string(i));
    state[i] = 1;
    int p = s.bones[i].parent;
    if (p >= 0 && p < n) visit(p);
    state[i] = 2;
    order.push_back(i);
  };
  for (int i = 0; i < n; ++i) visit(i);
  return order;
}

}  // namespace dfm
