// MEDIT .mesh (ASCII, 1-based): Vertices, Triangles, Tetrahedra; other standard sections are validated
// and skipped. Each element line ends with a reference (label) number, which is read and dropped.
#include <algorithm>
#include <cctype>
#include <iomanip>

#include "core/mesh/io_formats.h"
#include "core/mesh/io_parse.h"
#include "core/util/atomic_file.h"

namespace dfm::io {
namespace {

bool same_word(std::string_view a, const char* b) {
  std::string_view bv(b);
  return a.size() == bv.size() &&
         std::equal(a.begin(), a.end(), bv.begin(), [](char x, char y) { return std::tolower(x) == std::tolower(y); });
}

// Reads `n` elements of `k` vertex indices + reference into rows of `out` (0-based), checking range.
void read_elements(Tokenizer& tk, int k, long long n, int nv, const char* name, Eigen::MatrixXi& out) {
  out.resize(n, k);
  for (long long e = 0; e < n; ++e) {
    const auto vertex = [&] { return std::string(name) + " " + std::to_string(e + 1) + " vertex"; };
    for (int c = 0; c < k; ++c) {
      const long long v = tk.integer_or(vertex);
      if (v < 1 || v > nv)
        tk.fail(std::string(name) + " " + std::to_string(e + 1) + " has vertex index " + std::to_string(v) +
                " out of range [1, " + std::to_string(nv) + "]");
      out(e, c) = static_cast<int>(v - 1);
    }
    tk.integer_or([&] { return std::string(name) + " " + std::to_string(e + 1) + " reference"; });
  }
}

struct SkipSection {
  const char* name;
  int ints;   // integers per entry (vertex indices or references)
  int reals;  // reals per entry
};
const SkipSection kSkipped[] = {{"Corners", 1, 0},          {"RequiredVertices", 1, 0}, {"Ridges", 1, 0},
                                {"RequiredEdges", 1, 0},    {"RequiredTriangles", 1, 0}, {"Normals", 0, 3},
                                {"NormalAtVertices", 2, 0}, {"Tangents", 0, 3},        {"TangentAtVertices", 2, 0},
                                {"Hexahedra", 9, 0},        {"Prisms", 7, 0},           {"Edges", 3, 0}};

// The Vertices section (after its keyword): count, then x y z reference per vertex.
void read_vertices(Tokenizer& tk, Eigen::MatrixXd& V) {
  const long long n = tk.integer("vertex count");
  check_count(tk.path(), tk.line(), n, 8, tk.bytes_left(), "vertex");
  V.resize(n, 3);
  for (long long i = 0; i < n; ++i) {
    const auto coordinate = [i] { return "vertex " + std::to_string(i + 1) + " coordinate"; };
    for (int c = 0; c < 3; ++c) V(i, c) = tk.real_or(coordinate);
    tk.integer_or([i] { return "vertex " + std::to_string(i + 1) + " reference"; });
  }
}

// A Triangles, Quadrilaterals or Tetrahedra section (after its keyword `tok`): tets into m.T, faces
// (quads split along their 0-2 diagonal) appended to tris.
void read_element_section(Tokenizer& tk, std::string_view tok, TetMesh& m, bool& have_t, std::vector<Eigen::MatrixXi>& tris) {
  const bool tet = same_word(tok, "Tetrahedra"), quad = same_word(tok, "Quadrilaterals");
  const char* name = tet ? "tetrahedron" : quad ? "quadrilateral" : "triangle";
  const long long n = tk.integer(std::string(name) + " count");
  const int k = (tet || quad) ? 4 : 3;
  check_count(tk.path(), tk.line(), n, 2 * (k + 1), tk.bytes_left(), name);
  Eigen::MatrixXi E;
  read_elements(tk, k, n, m.num_vertices(), name, E);
  if (tet) {
    if (have_t) tk.fail("second Tetrahedra section");
    m.T = E;
    have_t = true;
  } else if (quad) {
    Eigen::MatrixXi Q(2 * n, 3);
    for (long long i = 0; i < n; ++i) {
      Q.row(2 * i) << E(i, 0), E(i, 1), E(i, 2);
      Q.row(2 * i + 1) << E(i, 0), E(i, 2), E(i, 3);
    }
    tris.push_back(Q);
  } else {
    tris.push_back(E);
  }
}

// A section read only to be validated and dropped (kSkipped), after its keyword `tok`.
void skip_section(Tokenizer& tk, std::string_view tok, int nv) {
  const SkipSection* s = nullptr;
  for (const SkipSection& c : kSkipped)
    if (same_word(tok, c.name)) s = &c;
  if (!s) tk.fail("unknown MEDIT keyword " + quote(tok));
  const long long n = tk.integer(std::string(s->name) + " count");
  check_count(tk.path(), tk.line(), n, 2 * (s->ints + s->reals), tk.bytes_left(), s->name);
  // Entries that name vertices are range-checked: edge endpoints, corner and required-vertex lists.
  const int checked = same_word(tok, "Edges")                                             ? 2
                      : (same_word(tok, "Corners") || same_word(tok, "RequiredVertices")) ? 1
                                                                                          : 0;
  for (long long i = 0; i < n; ++i) {
    const auto entry = [&] { return std::string(s->name) + " entry " + std::to_string(i + 1); };
    for (int c = 0; c < s->ints; ++c) {
      const long long v = tk.integer_or(entry);
      if (c < checked && (v < 1 || v > nv))
        tk.fail(entry() + " has vertex index " + std::to_string(v) + " out of range [1, " + std::to_string(nv) + "]");
    }
    for (int c = 0; c < s->reals; ++c) tk.real_or(entry);
  }
}

Eigen::MatrixXi stack_rows(const std::vector<Eigen::MatrixXi>& parts) {
  Eigen::Index rows = 0;
  for (const auto& t : parts) rows += t.rows();
  Eigen::MatrixXi out(rows, 3);
  rows = 0;
  for (const auto& t : parts) {
    out.middleRows(rows, t.rows()) = t;
    rows += t.rows();
  }
  return out;
}

}  // namespace

TetMesh read_medit(const std::string& path) {
  const std::string data = read_file(path);
  Tokenizer tk(path, data, true);
  TetMesh m;
  bool have_v = false, have_t = false;
  std::string_view tok;
  std::vector<Eigen::MatrixXi> tris;
  while (tk.next(tok)) {
    if (same_word(tok, "End")) break;
    if (same_word(tok, "MeshVersionFormatted")) {
      tk.integer("mesh version");
    } else if (same_word(tok, "Dimension")) {
      const long long d = tk.integer("dimension");
      if (d != 3) tk.fail("dimension " + std::to_string(d) + " is not supported (only 3)");
    } else if (same_word(tok, "Vertices")) {
      if (have_v) tk.fail("second Vertices section");
      read_vertices(tk, m.V);
      have_v = true;
    } else if (same_word(tok, "Triangles") || same_word(tok, "Tetrahedra") || same_word(tok, "Quadrilaterals")) {
      if (!have_v) tk.fail(std::string(tok) + " section before the Vertices section");
      read_element_section(tk, tok, m, have_t, tris);
    } else {
      skip_section(tk, tok, m.num_vertices());
    }
  }
  if (!have_v) throw file_error(path, 0, "no Vertices section (not a MEDIT mesh?)");
  if (!have_t) throw file_error(path, 0, "no Tetrahedra section (a surface-only .mesh is not a tet mesh)");
  m.F = stack_rows(tris);
  orient_tets_positively(m.V, m.T);
  return m;
}

void write_medit(const std::string& path, const TetMesh& m) {
  write_file_atomic(path, [&](std::ostream& o) {
    o << std::setprecision(17) << "MeshVersionFormatted 1\nDimension 3\nVertices\n" << m.V.rows() << "\n";
    for (int i = 0; i < m.V.rows(); ++i) o << m.V(i, 0) << ' ' << m.V(i, 1) << ' ' << m.V(i, 2) << " 0\n";
    if (m.F.rows() > 0) {
      o << "Triangles\n" << m.F.rows() << "\n";
      for (int i = 0; i < m.F.rows(); ++i)
        o << m.F(i, 0) + 1 << ' ' << m.F(i, 1) + 1 << ' ' << m.F(i, 2) + 1 << " 0\n";
    }
    o << "Tetrahedra\n" << m.T.rows() << "\n";
    for (int i = 0; i < m.T.rows(); ++i)
      o << m.T(i, 0) + 1 << ' ' << m.T(i, 1) + 1 << ' ' << m.T(i, 2) + 1 << ' ' << m.T(i, 3) + 1 << " 0\n";
    o << "End\n";
  });
}

}  // namespace dfm::io
