// PLY, ascii and binary (little or big endian). The header is parsed and checked first (format, element
// counts against the file size, property types), then the body is read with bounds checks, so errors
// name a line (ascii) or a byte offset (binary). Needs element "vertex" with x, y, z (nx, ny, nz kept as
// normals when all three are present) and, optionally, element "face" with a list property
// "vertex_indices" (or "vertex_index"); polygons are fan-triangulated; other elements are skipped.
#include <algorithm>
#include <climits>
#include <cmath>
#include <iomanip>

#include "core/mesh/io_binary.h"
#include "core/mesh/io_formats.h"
#include "core/mesh/io_parse.h"
#include "core/util/atomic_file.h"

namespace dfm::io {
namespace {

enum class Fmt { Ascii, BinLE, BinBE };

struct Type {
  int size = 0;
  bool integral = true;
  bool is_signed = true;
};

bool parse_type(std::string_view s, Type& t) {
  struct N { const char* a; const char* b; Type t; };
  static const N names[] = {{"char", "int8", {1, true, true}},      {"uchar", "uint8", {1, true, false}},
                            {"short", "int16", {2, true, true}},    {"ushort", "uint16", {2, true, false}},
                            {"int", "int32", {4, true, true}},      {"uint", "uint32", {4, true, false}},
                            {"float", "float32", {4, false, true}}, {"double", "float64", {8, false, true}}};
  for (const N& n : names)
    if (s == n.a || s == n.b) {
      t = n.t;
      return true;
    }
  return false;
}

struct Prop {
  std::string name;
  Type type;
  bool list = false;
  Type count_type;
};

struct Element {
  std::string name;
  long long count = 0;
  long line = 0;
  std::vector<Prop> props;
};

// Reads one scalar of `t` from the body, as a double.
class Body {
 public:
  Body(const std::string& path, std::string_view data, size_t start, long start_line, Fmt fmt)
      : fmt_(fmt), tk_(path, data.substr(start), false, start_line), bc_(path, data, start) {}

  double get(const Type& t, const std::string& what) {
    if (fmt_ == Fmt::Ascii) {
      std::string_view s = tk_.expect(what);
      double v;
      if (!parse_double(s, v)) tk_.fail("expected a number for " + what + ", found " + quote(s));
      if (t.integral && v != std::floor(v)) tk_.fail(what + " must be an integer, found " + quote(s));
      return v;
    }
    const bool le = fmt_ == Fmt::BinLE;
    unsigned char b[8];
    bc_.read(b, t.size, le, what);
    if (!t.integral) {
      if (t.size == 4) {
        float f;
        std::memcpy(&f, b, 4);
        return f;
      }
      double d;
      std::memcpy(&d, b, 8);
      return d;
    }
    switch (t.size) {
      case 1: return t.is_signed ? double(int8_t(b[0])) : double(b[0]);
      case 2: {
        uint16_t u;
        std::memcpy(&u, b, 2);
        return t.is_signed ? double(int16_t(u)) : double(u);
      }
      default: {
        uint32_t u;
        std::memcpy(&u, b, 4);
        return t.is_signed ? double(int32_t(u)) : double(u);
      }
    }
  }
  // Where the last value came from, for errors: fails at the current line or just before the offset.
  [[noreturn]] void fail(const std::string& problem, int last_size) {
    if (fmt_ == Fmt::Ascii) tk_.fail(problem);
    bc_.fail(bc_.pos() - last_size, problem);
  }
  long long bytes_left() const { return fmt_ == Fmt::Ascii ? tk_.bytes_left() : static_cast<long long>(bc_.left()); }

 private:
  Fmt fmt_;
  Tokenizer tk_;
  ByteCursor bc_;
};

// ---- header

struct Header {
  Fmt fmt = Fmt::Ascii;
  std::vector<Element> elements;
  size_t bytes = 0;    // the body starts here, just after the end_header line
  long body_line = 0;  // the body's first line (ascii)
};

// "format <ascii|binary_little_endian|binary_big_endian> 1.0"; line: for errors.
Fmt parse_format(const std::string& path, long line_no, std::string_view line, const std::vector<std::string_view>& t) {
  auto fail = [&](const std::string& p) { throw file_error(path, line_no, p); };
  Fmt fmt = Fmt::Ascii;
  if (t.size() != 3) fail("bad format line " + quote(line));
  if (t[1] == "ascii") fmt = Fmt::Ascii;
  else if (t[1] == "binary_little_endian") fmt = Fmt::BinLE;
  else if (t[1] == "binary_big_endian") fmt = Fmt::BinBE;
  else fail("unknown PLY format " + quote(t[1]));
  if (t[2] != "1.0") fail("unsupported PLY version " + quote(t[2]));
  return fmt;
}

// "property <type> <name>" or "property list <count type> <type> <name>".
Prop parse_property(const std::string& path, long line_no, std::string_view line, const std::vector<std::string_view>& t) {
  auto fail = [&](const std::string& p) { throw file_error(path, line_no, p); };
  Prop p;
  if (t.size() == 5 && t[1] == "list") {
    if (!parse_type(t[2], p.count_type) || !p.count_type.integral) fail("bad list count type " + quote(t[2]));
    if (!parse_type(t[3], p.type)) fail("unknown property type " + quote(t[3]));
    p.list = true;
    p.name = t[4];
  } else if (t.size() == 3) {
    if (!parse_type(t[1], p.type)) fail("unknown property type " + quote(t[1]));
    p.name = t[2];
  } else {
    fail("bad property line " + quote(line));
  }
  return p;
}

Header read_header(const std::string& path, const std::string& data) {
  LineReader lr(data);
  std::string_view line;
  std::vector<std::string_view> t;
  auto fail = [&](const std::string& p) { throw file_error(path, lr.line(), p); };
  if (data.empty()) throw file_error(path, 0, "empty file");
  if (!lr.next(line) || line != "ply") fail("not a PLY file (first line must be \"ply\")");
  Header h;
  bool have_format = false, have_end = false;
  while (!have_end && lr.next(line)) {
    split_ws(line, t);
    if (t.empty()) continue;
    if (t[0] == "comment" || t[0] == "obj_info") continue;
    if (t[0] == "format") {
      h.fmt = parse_format(path, lr.line(), line, t);
      have_format = true;
    } else if (t[0] == "element") {
      long long n = 0;  // (fail throws; clang cannot see that through the lambda)
      if (t.size() != 3 || !parse_int(t[2], n)) fail("bad element line " + quote(line));
      if (n < 0 || n > INT_MAX) fail("element " + quote(t[1]) + " count " + std::string(t[2]) + " out of range");
      h.elements.push_back({std::string(t[1]), n, lr.line(), {}});
    } else if (t[0] == "property") {
      if (h.elements.empty()) fail("property before any element");
      h.elements.back().props.push_back(parse_property(path, lr.line(), line, t));
    } else if (t[0] == "end_header") {
      have_end = true;
    } else {
      fail("unknown PLY header line " + quote(line));
    }
  }
  if (!have_end) throw file_error(path, lr.line(), "header has no end_header line (truncated?)");
  if (!have_format) throw file_error(path, lr.line(), "header has no format line");
  h.bytes = data.size() - static_cast<size_t>(lr.bytes_left() < 0 ? 0 : lr.bytes_left());
  h.body_line = lr.line() + 1;
  return h;
}

// Element counts against the body's size (each value takes at least a byte or two), before anything
// is allocated for them.
void check_element_sizes(const std::string& path, const Header& h, long long body_bytes) {
  for (const Element& e : h.elements) {
    long long min_bytes = 0;  // per element: a binary list needs its count; ascii needs 2 chars per value
    for (const Prop& p : e.props) min_bytes += h.fmt == Fmt::Ascii ? 2 : (p.list ? p.count_type.size : p.type.size);
    check_count(path, e.line, e.count, min_bytes, body_bytes, "element " + quote(e.name));
    if (e.props.empty() && e.count > 0) throw file_error(path, e.line, "element " + quote(e.name) + " has no properties");
  }
}

// Which element holds the vertices, and which of its properties are x, y, z and the normal (-1: none).
struct VertexLayout {
  const Element* element = nullptr;
  int ix = -1, iy = -1, iz = -1, inx = -1, iny = -1, inz = -1;
  bool normals() const { return inx >= 0 && iny >= 0 && inz >= 0; }
};

VertexLayout vertex_layout(const std::string& path, const std::vector<Element>& elements) {
  VertexLayout L;
  for (const Element& e : elements)
    if (e.name == "vertex") {
      L.element = &e;
      for (int i = 0; i < static_cast<int>(e.props.size()); ++i) {
        const std::string& n = e.props[i].name;
        if (e.props[i].list) continue;
        int* slot = n == "x" ? &L.ix : n == "y" ? &L.iy : n == "z" ? &L.iz : n == "nx" ? &L.inx : n == "ny" ? &L.iny : n == "nz" ? &L.inz : nullptr;
        if (slot) *slot = i;
      }
      if (L.ix < 0 || L.iy < 0 || L.iz < 0) throw file_error(path, e.line, "element vertex lacks an x, y or z property");
    }
  if (!L.element || L.element->count == 0) throw file_error(path, 0, "no vertices (missing or empty element vertex)");
  return L;
}

// ---- body

// Scalar property i of vertex k, into m when it is a coordinate or (with all three present) a normal.
void store_vertex_value(const VertexLayout& L, int i, long long k, double v, TriMesh& m) {
  const bool normals = L.normals();
  if (i == L.ix) m.V(k, 0) = v;
  if (i == L.iy) m.V(k, 1) = v;
  if (i == L.iz) m.V(k, 2) = v;
  if (normals && i == L.inx) m.N(k, 0) = v;
  if (normals && i == L.iny) m.N(k, 1) = v;
  if (normals && i == L.inz) m.N(k, 2) = v;
}

// One list property. indices: it is the face's vertex list, checked against the vertex count and
// fan-triangulated into F; any other list is read and dropped.
void read_list(Body& body, const Prop& p, const std::string& what, bool indices, long long num_vertices,
               std::vector<int>& poly, std::vector<int>& F) {
  double n = body.get(p.count_type, what + " list length");
  if (n < 0 || n > body.bytes_left())
    body.fail(what + " list length " + num(n) + " is impossible (" + std::to_string(body.bytes_left()) + " bytes left)",
              p.count_type.size);
  if (indices && n < 3) body.fail(what + " has " + num(n) + " vertices (at least 3 needed)", p.count_type.size);
  poly.clear();
  for (long long j = 0; j < static_cast<long long>(n); ++j) {
    double v = body.get(p.type, what + " list entry");
    if (!indices) continue;
    if (!(v >= 0 && v < num_vertices && v == std::floor(v)))
      body.fail(what + " has vertex index " + num(v) + " out of range [0, " + std::to_string(num_vertices - 1) + "]",
                p.type.size);
    poly.push_back(static_cast<int>(v));
  }
  for (size_t j = 1; j + 1 < poly.size(); ++j) F.insert(F.end(), {poly[0], poly[j], poly[j + 1]});
}

// Every element's values in file order: the vertices (and normals) into m, the faces' triangles
// returned; the other elements' values are read (and checked) and dropped.
std::vector<int> read_elements(const std::string& path, const std::vector<Element>& elements, const VertexLayout& L,
                               Body& body, TriMesh& m) {
  std::vector<int> F, poly;
  int iface = -1;
  for (const Element& e : elements) {
    const bool is_v = &e == L.element, is_f = e.name == "face";
    if (is_f) {
      for (int i = 0; i < static_cast<int>(e.props.size()); ++i)
        if (e.props[i].list && (e.props[i].name == "vertex_indices" || e.props[i].name == "vertex_index")) iface = i;
      if (iface < 0) throw file_error(path, e.line, "element face lacks a list property vertex_indices");
    }
    for (long long k = 0; k < e.count; ++k) {
      const std::string what = e.name + " " + std::to_string(k);
      for (int i = 0; i < static_cast<int>(e.props.size()); ++i) {
        const Prop& p = e.props[i];
        if (p.list) {
          read_list(body, p, what, is_f && i == iface, L.element->count, poly, F);
          continue;
        }
        double v = body.get(p.type, what + " property " + p.name);
        if (is_v && !std::isfinite(v)) body.fail(what + " property " + p.name + " is not finite", p.type.size);
        if (is_v) store_vertex_value(L, i, k, v, m);
      }
    }
  }
  return F;
}

}  // namespace

TriMesh read_ply(const std::string& path) {
  const std::string data = read_file(path);
  const Header header = read_header(path, data);
  const long long body_bytes = static_cast<long long>(data.size() - std::min(header.bytes, data.size()));
  check_element_sizes(path, header, body_bytes);
  const VertexLayout layout = vertex_layout(path, header.elements);

  TriMesh m;
  m.V.resize(layout.element->count, 3);
  if (layout.normals()) m.N.resize(layout.element->count, 3);
  Body body(path, data, header.bytes, header.body_line, header.fmt);
  std::vector<int> F = read_elements(path, header.elements, layout, body, m);
  if (F.empty()) throw file_error(path, 0, "no faces (a surface needs at least one triangle)");
  m.F = Eigen::Map<Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>>(F.data(), F.size() / 3, 3);
  return m;
}

void write_ply(const std::string& path, const TriMesh& m, bool binary) {
  const bool normals = m.N.rows() == m.V.rows() && m.N.rows() > 0;
  write_file_atomic(
      path,
      [&](std::ostream& o) {
        o << "ply\nformat " << (binary ? "binary_little_endian" : "ascii") << " 1.0\ncomment written by deform\n"
          << "element vertex " << m.V.rows() << "\nproperty double x\nproperty double y\nproperty double z\n";
        if (normals) o << "property double nx\nproperty double ny\nproperty double nz\n";
        o << "element face " << m.F.rows() << "\nproperty list uchar int vertex_indices\nend_header\n";
        if (!binary) {
          o << std::setprecision(17);
          for (int i = 0; i < m.V.rows(); ++i) {
            o << m.V(i, 0) << ' ' << m.V(i, 1) << ' ' << m.V(i, 2);
            if (normals) o << ' ' << m.N(i, 0) << ' ' << m.N(i, 1) << ' ' << m.N(i, 2);
            o << '\n';
          }
          for (int f = 0; f < m.F.rows(); ++f) o << "3 " << m.F(f, 0) << ' ' << m.F(f, 1) << ' ' << m.F(f, 2) << '\n';
          return;
        }
        auto put = [&](const void* p, size_t n) {
          unsigned char b[8];
          std::memcpy(b, p, n);
          if (!host_is_little_endian()) std::reverse(b, b + n);
          o.write(reinterpret_cast<const char*>(b), n);
        };
        for (int i = 0; i < m.V.rows(); ++i) {
          for (int c = 0; c < (normals ? 6 : 3); ++c) {
            const double v = c < 3 ? m.V(i, c) : m.N(i, c - 3);
            put(&v, 8);
          }
        }
        for (int f = 0; f < m.F.rows(); ++f) {
          const unsigned char three = 3;
          o.write(reinterpret_cast<const char*>(&three), 1);
          for (int c = 0; c < 3; ++c) {
            int32_t v = m.F(f, c);
            put(&v, 4);
          }
        }
      },
      binary);
}

}  // namespace dfm::io
