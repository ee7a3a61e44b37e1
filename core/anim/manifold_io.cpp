#include "core/anim/manifold_io.h"

#include <charconv>
#include <fstream>
#include <sstream>
#include <string_view>

#include "core/util/atomic_file.h"
#include "core/util/error.h"

namespace dfm {

namespace {

// Appends the shortest round-trip text of a number.
template <class Num>
void put(std::string& buf, Num x) {
  char tmp[32];
  auto r = std::to_chars(tmp, tmp + sizeof tmp, x);
  buf.append(tmp, r.ptr);
}

// Line-by-line reader over the whole file held in memory (tet4 files can be hundreds of MB).
class Lines {
 public:
  Lines(std::string path, std::string text) : path_(std::move(path)), text_(std::move(text)) {}
  // Next non-empty, non-comment line split into tokens; false at end of file.
  bool next(std::vector<std::string_view>& tok) {
    while (pos_ < text_.size()) {
      size_t end = text_.find('\n', pos_);
      if (end == std::string::npos) end = text_.size();
      std::string_view line(text_.data() + pos_, end - pos_);
      pos_ = end + 1;
      ++line_;
      tok.clear();
      size_t i = 0;
      while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
        size_t j = i;
        while (j < line.size() && line[j] != ' ' && line[j] != '\t' && line[j] != '\r') ++j;
        if (j > i) tok.push_back(line.substr(i, j - i));
        i = j;
      }
      if (tok.empty() || tok[0][0] == '#') continue;
      return true;
    }
    return false;
  }
  void expect(std::vector<std::string_view>& tok, const char* what) {
    if (!next(tok)) throw error(std::string("unexpected end of file, expected ") + what);
  }
  template <class Num>
  Num number(std::string_view s, const char* what) const {
    Num x{};
    auto r = std::from_chars(s.data(), s.data() + s.size(), x);
    if (r.ec != std::errc() || r.ptr != s.data() + s.size())
      throw error(std::string("bad ") + what + " '" + std::string(s) + "'");
    return x;
  }
  Error error(const std::string& msg) const { return file_error(path_, line_, msg); }
  // A line 'NAME <count>' with 0 <= count <= 2e9.
  int count(std::vector<std::string_view>& tok, const char* name) {
    expect(tok, name);
    if (tok.size() != 2 || tok[0] != name) throw error(std::string("expected '") + name + " <count>'");
    const long long n = number<long long>(tok[1], "count");
    if (n < 0 || n > 2000000000LL) throw error(std::string(name) + " count out of range");
    return static_cast<int>(n);
  }

 private:
  std::string path_, text_;
  size_t pos_ = 0;
  long line_ = 0;
};

// Version 2's closing sections: the layers' triangle lists, each slab's prism entry and the key layers
// (manifold.h).
// Index ranges are checked here; validate_manifold checks them against the layers.
void read_prism_slabs(Lines& L, std::vector<std::string_view>& tok, AnimationManifold& M) {
  auto count = [&](const char* name) { return L.count(tok, name); };
  const int ns = count("surfaces");
  for (int i = 0; i < ns; ++i) {
    const int nf = count("surface");
    Eigen::MatrixXi F(nf, 3);
    for (int f = 0; f < nf; ++f) {
      L.expect(tok, "a triangle line 'f A B C'");
      if (tok.size() != 4 || tok[0] != "f") throw L.error("expected a triangle line 'f A B C'");
      for (int d = 0; d < 3; ++d) F(f, d) = L.number<int>(tok[d + 1], "vertex index");
    }
    M.layer_faces.push_back(std::move(F));
  }
  const int np = count("prisms");
  if (np != 0 && np != M.num_slabs())
    throw L.error("prisms: " + std::to_string(np) + " entries for " + std::to_string(M.num_slabs()) + " slabs");
  for (int i = 0; i < np; ++i) {
    L.expect(tok, "a line 'prism FACES LOWER UPPER COUNT'");
    if (tok.size() != 5 || tok[0] != "prism") throw L.error("expected 'prism FACES LOWER UPPER COUNT'");
    PrismSlab p;
    p.faces = L.number<int>(tok[1], "triangle list index");
    p.lower = L.number<int>(tok[2], "first lower vertex");
    p.upper = L.number<int>(tok[3], "first upper vertex");
    p.count = L.number<int>(tok[4], "layer vertex count");
    if (p.faces < -1 || p.faces >= ns) throw L.error("prism: triangle list " + std::to_string(p.faces) + " does not exist");
    M.prism_slabs.push_back(p);
  }
  const int nk = count("keys");
  for (int i = 0; i < nk; ++i) {
    L.expect(tok, "a line 'key TIME FACES N'");
    if (tok.size() != 4 || tok[0] != "key") throw L.error("expected 'key TIME FACES N'");
    ManifoldKey k;
    k.time = L.number<double>(tok[1], "key time");
    k.faces = L.number<int>(tok[2], "triangle list index");
    const int n = L.number<int>(tok[3], "key vertex count");
    if (k.faces < 0 || k.faces >= ns) throw L.error("key: triangle list " + std::to_string(k.faces) + " does not exist");
    if (n < 0 || n > 2000000000) throw L.error("key vertex count out of range");
    k.vertices.resize(n);
    for (int v = 0; v < n; ++v) {
      L.expect(tok, "a key vertex line 'k V'");
      if (tok.size() != 2 || tok[0] != "k") throw L.error("expected a key vertex line 'k V'");
      k.vertices[v] = L.number<int>(tok[1], "vertex index");
    }
    M.key_layers.push_back(std::move(k));
  }
}

}  // namespace

namespace {

// Text lines (a tag, then numbers) into a stream through a 1 MiB buffer.
class LineWriter {
 public:
  explicit LineWriter(std::ostream& os) : os_(os) { buf_.reserve(1 << 20); }
  template <class... Num>
  void line(const char* tag, Num... xs) {
    buf_ += tag;
    ((buf_ += ' ', put(buf_, xs)), ...);
    end_line();
  }
  // A tag and the first n entries of row r (r(d) for d < n).
  template <class Row>
  void row(const char* tag, const Row& r, int n) {
    buf_ += tag;
    for (int d = 0; d < n; ++d) buf_ += ' ', put(buf_, r(d));
    end_line();
  }
  void flush() {
    os_.write(buf_.data(), static_cast<std::streamsize>(buf_.size()));
    buf_.clear();
  }

 private:
  void end_line() {
    buf_ += '\n';
    if (buf_.size() > (1u << 20)) flush();
  }
  std::ostream& os_;
  std::string buf_;
};

void write_geometry(LineWriter& w, const AnimationManifold& M) {
  w.line("vertices", M.num_vertices());
  w.line("tets", M.num_tets());
  w.line("layers", M.num_layers());
  for (int i = 0; i < M.num_layers(); ++i) w.line("layer", M.times[i], M.slab_offsets[i]);
  for (int v = 0; v < M.num_vertices(); ++v) w.row("v", [&](int d) { return M.V(v, d); }, 4);
  for (int k = 0; k < M.num_tets(); ++k) w.row("t", [&](int d) { return M.T(k, d); }, 4);
}

// Version 2's sections: the layers' triangle lists, each slab's prism record, the keys' layers.
void write_layers(LineWriter& w, const AnimationManifold& M) {
  w.line("surfaces", static_cast<int>(M.layer_faces.size()));
  for (const Eigen::MatrixXi& F : M.layer_faces) {
    w.line("surface", static_cast<int>(F.rows()));
    for (Eigen::Index f = 0; f < F.rows(); ++f) w.row("f", [&](int d) { return F(f, d); }, 3);
  }
  w.line("prisms", static_cast<int>(M.prism_slabs.size()));
  for (const PrismSlab& p : M.prism_slabs) w.line("prism", p.faces, p.lower, p.upper, p.count);
  w.line("keys", static_cast<int>(M.key_layers.size()));
  for (const ManifoldKey& k : M.key_layers) {
    w.line("key", k.time, k.faces, static_cast<int>(k.vertices.size()));
    for (int v : k.vertices) w.line("k", v);
  }
}

}  // namespace

void write_manifold(const std::string& path, const AnimationManifold& M) {
  validate_manifold(M, path);
  write_file_atomic(path, [&](std::ostream& os) {
    LineWriter w(os);
    os << "tet4 2\n# animation manifold: 4D vertices (x y z t), oriented tetrahedra grouped in time slabs\n";
    write_geometry(w, M);
    write_layers(w, M);
    w.flush();
    if (!os) throw Error(path + ": write failed");
  });
}

AnimationManifold read_manifold(const std::string& path) {
  require_readable_file(path);
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  if (!in && !in.eof()) throw file_error(path, 0, "read failed");
  Lines L(path, ss.str());
  std::vector<std::string_view> tok;

  L.expect(tok, "the header 'tet4 2'");
  if (tok.size() != 2 || tok[0] != "tet4") throw L.error("not a tet4 file (expected the header 'tet4 2')");
  const int version = L.number<int>(tok[1], "version");
  if (version != 1 && version != 2) throw L.error("unsupported tet4 version " + std::string(tok[1]));
  auto count = [&](const char* name) { return L.count(tok, name); };
  const int nv = count("vertices");
  const int nt = count("tets");
  const int nl = count("layers");
  if (nl < 2) throw L.error("an animation manifold needs at least 2 layers");

  AnimationManifold M;
  M.times.resize(nl);
  M.slab_offsets.resize(nl);
  for (int i = 0; i < nl; ++i) {
    L.expect(tok, "a 'layer TIME FIRST_TET' line");
    if (tok.size() != 3 || tok[0] != "layer") throw L.error("expected 'layer TIME FIRST_TET'");
    M.times[i] = L.number<double>(tok[1], "layer time");
    M.slab_offsets[i] = L.number<int>(tok[2], "first tetrahedron index");
  }
  M.V.resize(nv, 4);
  for (int v = 0; v < nv; ++v) {
    L.expect(tok, "a vertex line 'v X Y Z T'");
    if (tok.size() != 5 || tok[0] != "v") throw L.error("expected a vertex line 'v X Y Z T'");
    for (int d = 0; d < 4; ++d) M.V(v, d) = L.number<double>(tok[d + 1], "coordinate");
  }
  M.T.resize(nt, 4);
  for (int k = 0; k < nt; ++k) {
    L.expect(tok, "a tetrahedron line 't A B C D'");
    if (tok.size() != 5 || tok[0] != "t") throw L.error("expected a tetrahedron line 't A B C D'");
    for (int d = 0; d < 4; ++d) {
      const int v = L.number<int>(tok[d + 1], "vertex index");
      if (v < 0 || v >= nv) throw L.error("vertex index " + std::to_string(v) + " outside [0, " + std::to_string(nv) + ")");
      M.T(k, d) = v;
    }
  }
  if (version >= 2) read_prism_slabs(L, tok, M);
  if (L.next(tok)) throw L.error("unexpected content after the last tetrahedron");
  validate_manifold(M, path);
  return M;
}

}  // namespace dfm
