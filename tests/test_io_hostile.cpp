// Hostile input: every reader gives a dfm::Error naming the file, the problem and (where it applies) the
// line or byte offset; nothing crashes, hangs or allocates what the file cannot hold.
// Zero-area faces and zero-volume tets are accepted (mesh_info reports them), not errors.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>

#include <sys/stat.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "core/mesh/io.h"
#include "core/scene/scene_file.h"
#include "core/util/error.h"
#include "tests/fuzz/fuzz_scene_fixture.h"

using namespace dfm;
namespace fs = std::filesystem;
using Catch::Contains;

namespace {

fs::path dir() {
  static fs::path d = [] {
    fs::path p = fs::temp_directory_path() / ("dfm_test_io_hostile_" + std::to_string(::getpid()));
    fs::create_directories(p);
    return p;
  }();
  static const bool cleanup = [] {  // registered after d exists, so it runs before d is destroyed
    return std::atexit([] {
             std::error_code ec;
             fs::remove_all(d, ec);
           }) == 0;
  }();
  (void)cleanup;
  return d;
}

std::string put(const std::string& name, const std::string& bytes) {
  fs::path p = dir() / name;
  std::ofstream(p, std::ios::binary) << bytes;
  return p.string();
}

// Reads `path` with `read`, requires a dfm::Error whose message has every one of `parts`.
void require_error(const std::function<void()>& read, const std::vector<std::string>& parts) {
  try {
    read();
  } catch (const Error& e) {
    std::string msg = e.what();
    INFO("message: " << msg);
    for (const std::string& p : parts) CHECK_THAT(msg, Contains(p));
    return;
  }
  FAIL("no dfm::Error thrown; expected one containing " << parts[0]);
}

std::function<void()> surface(const std::string& p) { return [p] { read_surface(p); }; }
std::function<void()> tet(const std::string& p) { return [p] { read_tet_mesh(p); }; }
std::function<void()> dmat(const std::string& p) { return [p] { read_dmat(p); }; }
std::function<void()> tgf(const std::string& p) { return [p] { read_tgf(p); }; }

std::string le32(uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); }
std::string le64d(double v) { return std::string(reinterpret_cast<const char*>(&v), 8); }

}  // namespace

TEST_CASE("missing file, directory, empty file", "[io][hostile]") {
  require_error(surface((dir() / "nope.obj").string()), {"nope.obj", "no such file"});
  fs::create_directories(dir() / "adir.off");
  require_error(surface((dir() / "adir.off").string()), {"adir.off", "directory"});
  require_error(tet((dir() / "adir.off").string()), {"adir.off"});
  for (const char* n : {"empty.obj", "empty.off", "empty.ply", "empty.stl", "empty.mesh", "empty.dmat", "empty.tgf"}) {
    std::string p = put(n, "");
    INFO(n);
    std::string ext = fs::path(n).extension().string();
    auto f = ext == ".mesh" ? tet(p) : ext == ".dmat" ? dmat(p) : ext == ".tgf" ? tgf(p) : surface(p);
    require_error(f, {n});
  }
}

TEST_CASE("OBJ: out-of-range, negative and malformed indices, NaN, garbage", "[io][hostile]") {
  require_error(surface(put("oor.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n")),
                {"oor.obj:4:", "face 1 has vertex index 9 out of range [1, 3]"});
  require_error(surface(put("neg.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 1 2\n")),
                {"neg.obj:4:", "vertex index -4 out of range"});
  require_error(surface(put("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n")), {"zero.obj:4:", "vertex index 0"});
  require_error(surface(put("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n")),
                {"nan.obj:2:", "vertex 2", "not finite"});
  require_error(surface(put("inf.obj", "v 0 0 0\nv 1 -inf 0\nv 0 1 0\nf 1 2 3\n")), {"inf.obj:2:", "not finite"});
  require_error(surface(put("short.obj", "v 0 0 0\nv 1 0\n")), {"short.obj:2:", "vertex 2 needs 3 coordinates"});
  require_error(surface(put("two.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n")), {"two.obj:3:", "face 1 has 2 corners"});
  require_error(surface(put("word.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 x 3\n")), {"word.obj:4:", "bad corner 'x'"});
  require_error(surface(put("bin.obj", std::string("\x7f" "ELF\x02\x01\x01\0\0\0", 10) + "\xff\xfe garbage\n")),
                {"bin.obj:1:", "unknown OBJ statement"});
  require_error(surface(put("nofaces.obj", "v 0 0 0\n")), {"nofaces.obj", "no faces"});
  require_error(surface(put("min.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -9223372036854775808 1 2\n")),
                {"min.obj:4:", "vertex index -9223372036854775808 out of range"});
  require_error(surface(put("big.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 99999999999999999999 1 2\n")),
                {"big.obj:4:", "bad corner"});
}

TEST_CASE("OFF: enormous counts, truncation, wrong counts, bad indices", "[io][hostile]") {
  require_error(surface(put("huge.off", "OFF\n999999999999 1 0\n")), {"huge.off:2:", "999999999999", "too large"});
  require_error(surface(put("big.off", "OFF\n2000000000 2000000000 0\n0 0 0\n")),
                {"big.off:2:", "vertex count 2000000000 needs at least"});
  require_error(surface(put("negc.off", "OFF\n-3 1 0\n")), {"negc.off:2:", "negative vertex count"});
  require_error(surface(put("trunc.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n")),
                {"trunc.off", "face count 1 needs"});
  require_error(surface(put("trunc2.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n3 0 1               ")),
                {"trunc2.off:8:", "face 1 declares 3 vertices but lists 2"});
  require_error(surface(put("idx.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n")),
                {"idx.off:6:", "face 0 has vertex index 3 out of range [0, 2]"});
  require_error(surface(put("negi.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n")),
                {"negi.off:6:", "vertex index -1 out of range"});
  require_error(surface(put("nan.off", "OFF\n3 1 0\n0 0 0\n1 NaN 0\n0 1 0\n3 0 1 2\n")),
                {"nan.off:4:", "vertex 1", "not finite"});
  require_error(surface(put("hdr.off", "OFX\n3 1 0\n")), {"hdr.off:1:", "missing OFF header"});
  require_error(surface(put("deg.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1     \n")), {"deg.off:6:", "2 vertices"});
}

TEST_CASE("zero-area faces are accepted", "[io][hostile]") {
  TriMesh m = read_surface(put("flat.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n2 0 0\n3 0 1 2\n3 0 0 1\n"));
  REQUIRE(m.num_faces() == 2);
}

TEST_CASE("PLY: header problems, truncated binary, bad lists, NaN", "[io][hostile]") {
  const std::string head = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                           "property float y\nproperty float z\nelement face 1\n"
                           "property list uchar int vertex_indices\nend_header\n";
  std::string verts;
  for (float f : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) verts += std::string(reinterpret_cast<char*>(&f), 4);
  std::string face = std::string("\x03", 1) + le32(0) + le32(1) + le32(2);
  // The well-formed file reads; each variant below breaks one thing.
  REQUIRE(read_surface(put("ok.ply", head + verts + face)).num_faces() == 1);
  require_error(surface(put("trunc.ply", head + verts + face.substr(0, 7))),
                {"trunc.ply: byte offset 210", "unexpected end of file", "face 0"});
  require_error(surface(put("idx.ply", head + verts + std::string("\x03", 1) + le32(0) + le32(7) + le32(2))),
                {"idx.ply: byte offset 210", "face 0 has vertex index 7 out of range [0, 2]"});
  require_error(surface(put("list.ply", head + verts + std::string("\xff", 1) + le32(0) + le32(1) + le32(2))),
                {"list.ply: byte offset 205", "list length 255 is impossible"});
  std::string nanv = verts;
  float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(&nanv[16], &nan, 4);
  require_error(surface(put("nan.ply", head + nanv + face)), {"nan.ply: byte offset 185", "vertex 1 property y is not finite"});
  std::string huge = head;
  huge.replace(huge.find("vertex 3"), 8, "vertex 2147483647");
  require_error(surface(put("huge.ply", huge + verts + face)), {"huge.ply:3:", "2147483647 needs at least"});
  require_error(surface(put("nohead.ply", "ply\nformat ascii 1.0\nelement vertex 3\n")), {"nohead.ply", "no end_header"});
  require_error(surface(put("notply.ply", "plx\n")), {"notply.ply:1:", "not a PLY file"});
  require_error(surface(put("fmt.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n")), {"fmt.ply:2:", "unknown PLY format"});
  require_error(surface(put("type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n")),
                {"type.ply:4:", "unknown property type 'quad'"});
  require_error(surface(put("ascii.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                         "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                                         "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n")),
                {"ascii.ply:13:", "face 0 has vertex index 5 out of range [0, 2]"});
  require_error(surface(put("noxyz.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n0\n")),
                {"noxyz.ply:3:", "lacks an x, y or z"});
}

TEST_CASE("STL: wrong binary size, truncated ascii, NaN", "[io][hostile]") {
  std::string bin(80, ' ');
  bin += le32(2);
  bin += std::string(50, '\0');  // one triangle of the two announced
  require_error(surface(put("short.stl", bin)), {"short.stl: byte offset 80", "2 triangles", "needs 84 + 50 * 2 = 184 bytes",
                                                  "file has 134"});
  std::string huge(80, ' ');
  huge += le32(0xffffffffu);
  require_error(surface(put("huge.stl", huge)), {"huge.stl: byte offset 80", "4294967295 triangles"});
  require_error(surface(put("tiny.stl", "abc")), {"tiny.stl: byte offset 0", "too short for binary STL"});
  require_error(surface(put("trunc.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n")),
                {"trunc.stl", "unexpected end of file"});
  require_error(surface(put("nan.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex nan 0 0\n"
                                       "vertex 0 1 0\nendloop\nendfacet\nendsolid\n")),
                {"nan.stl:5:", "facet 1 vertex x is not finite"});
  require_error(surface(put("two.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                                       "endloop\nendfacet\nendsolid\n")),
                {"two.stl:6:", "facet 1 has 2 vertices"});
  std::string nanbin(80, ' ');
  nanbin += le32(1);
  float tri[12] = {0, 0, 1, 0, 0, 0, 1, 0, 0, 0, std::numeric_limits<float>::infinity(), 0};
  nanbin += std::string(reinterpret_cast<char*>(tri), 48) + std::string(2, '\0');
  require_error(surface(put("inf.stl", nanbin)), {"inf.stl: byte offset 124", "non-finite vertex coordinate"});
}

TEST_CASE("MEDIT .mesh: out-of-range tet index, truncation, huge counts, unknown sections", "[io][hostile]") {
  const std::string v = "MeshVersionFormatted 1\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n";
  REQUIRE(read_tet_mesh(put("ok.mesh", v + "Tetrahedra\n1\n1 2 3 4 0\nEnd\n")).num_tets() == 1);
  require_error(tet(put("oor.mesh", v + "Tetrahedra\n2\n1 2 3 4 0\n1 2 3 9999 0\nEnd\n")),
                {"oor.mesh:12:", "tetrahedron 2 has vertex index 9999 out of range [1, 4]"});
  require_error(tet(put("zero.mesh", v + "Tetrahedra\n1\n0 2 3 4 0\n")), {"zero.mesh:11:", "vertex index 0 out of range"});
  require_error(tet(put("trunc.mesh", v + "Tetrahedra\n2\n1 2 3 4 0\n1 2")), {"trunc.mesh", "tetrahedron count 2 needs"});
  require_error(tet(put("trunc2.mesh", v + "Tetrahedra\n1\n1 2 3          ")),
                {"trunc2.mesh:11:", "unexpected end of file", "tetrahedron 1 vertex"});
  require_error(tet(put("huge.mesh", "MeshVersionFormatted 1\nDimension 3\nVertices\n99999999999\n")),
                {"huge.mesh:4:", "vertex count 99999999999 is too large"});
  require_error(tet(put("nan.mesh", "MeshVersionFormatted 1\nDimension 3\nVertices\n1\n0 inf 0 0\n")),
                {"nan.mesh:5:", "vertex 1 coordinate is not finite"});
  require_error(tet(put("kw.mesh", v + "Blobs\n3\n")), {"kw.mesh:9:", "unknown MEDIT keyword 'Blobs'"});
  require_error(tet(put("dim.mesh", "MeshVersionFormatted 1\nDimension 2\n")), {"dim.mesh:2:", "dimension 2"});
  require_error(tet(put("notet.mesh", v + "End\n")), {"notet.mesh", "no Tetrahedra section"});
  require_error(tet(put("order.mesh", "Triangles\n1\n1 2 3 0\n")), {"order.mesh:1:", "before the Vertices section"});
  // A zero-volume tet is accepted as is.
  REQUIRE(read_tet_mesh(put("flat.mesh", v + "Tetrahedra\n1\n1 2 2 4 0\nEnd\n")).num_tets() == 1);
}

TEST_CASE("TetGen .node/.ele: missing partner, bad indices", "[io][hostile]") {
  put("a.node", "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n");
  require_error(tet((dir() / "a.node").string()), {"a.ele", "no such file"});
  put("a.ele", "1 4 0\n1 1 2 3 5\n");
  require_error(tet((dir() / "a.ele").string()), {"a.ele:2:", "tetrahedron 1 has vertex index 5 out of range [1, 4]"});
  put("b.node", "4 3 0 0\n1 0 0 0\n2 1 0 0\n7 0 1 0\n4 0 0 1\n");
  require_error(tet((dir() / "b.node").string()), {"b.node:4:", "point index 7 out of sequence"});
  put("c.node", "4 2 0 0\n");
  require_error(tet((dir() / "c.node").string()), {"c.node:1:", "dimension 2"});
}

TEST_CASE("dmat: truncated binary, wrong counts, NaN, garbage", "[io][hostile]") {
  require_error(dmat(put("tb.dmat", "0 0\n2 3\n" + le64d(1) + le64d(2))),
                {"tb.dmat: byte offset 8", "needs 48 bytes", "file has 16", "truncated"});
  require_error(dmat(put("nanb.dmat", "0 0\n1 2\n" + le64d(1) + le64d(std::nan("")))),
                {"nanb.dmat: byte offset 16", "entry (row 2, column 1) is not finite"});
  require_error(dmat(put("short.dmat", "2 2\n1\n2\n3\n")), {"short.dmat", "matrix entry count 4 needs"});
  require_error(dmat(put("short2.dmat", "1 3\n1\n2\n          ")), {"short2.dmat:4:", "unexpected end of file", "row 3, column 1"});
  require_error(dmat(put("long.dmat", "1 2\n1\n2\n3\n")), {"long.dmat:4:", "more entries than 2 x 1"});
  require_error(dmat(put("nan.dmat", "1 2\n1\nnan\n")), {"nan.dmat:3:", "(row 2, column 1) is not finite"});
  require_error(dmat(put("word.dmat", "1 2\n1\nabc\n")), {"word.dmat:3:", "expected a number", "'abc'"});
  require_error(dmat(put("huge.dmat", "4000000000 1\n")), {"huge.dmat:1:", "too large"});
  require_error(dmat(put("hugeb.dmat", "0 0\n2000000000 2000000000\n" + le64d(1))),
                {"hugeb.dmat: byte offset 26", "needs too many bytes", "truncated"});
  require_error(dmat(put("neg.dmat", "-1 3\n")), {"neg.dmat:1:", "negative size"});
  require_error(dmat(put("garb.dmat", std::string("\x89PNG\r\n\x1a\n\0\0", 10))), {"garb.dmat:1:", "expected an integer"});
}

TEST_CASE("tgf: bad joints, out-of-range edges, self loops", "[io][hostile]") {
  require_error(tgf(put("oor.tgf", "1 0 0 0\n2 1 0 0\n#\n1 3\n")), {"oor.tgf:4:", "edge 1 has joint index 3 out of range [1, 2]"});
  require_error(tgf(put("neg.tgf", "1 0 0 0\n2 1 0 0\n#\n-1 2\n")), {"neg.tgf:4:", "joint index -1 out of range"});
  require_error(tgf(put("nan.tgf", "1 0 0 0\n2 nan 0 0\n#\n1 2\n")), {"nan.tgf:2:", "joint 2 coordinate is not finite"});
  require_error(tgf(put("few.tgf", "1 0 0\n")), {"few.tgf:1:", "joint 1 needs"});
  require_error(tgf(put("loop.tgf", "1 0 0 0\n2 1 0 0\n#\n2 2\n")), {"loop.tgf:4:", "joins joint 2 to itself"});
  require_error(tgf(put("flag.tgf", "1 0 0 0\n2 1 0 0\n#\n1 2 7 0 0\n")), {"flag.tgf:4:", "flag must be 0 or 1"});
  require_error(tgf(put("none.tgf", "#\n#\n")), {"none.tgf", "no joints"});
}

TEST_CASE("points: wrong field counts and non-numbers", "[io][hostile]") {
  require_error([p = put("p.txt", "1 2 3\n# comment\n\n4 5\n")] { read_points(p); }, {"p.txt:4:", "point 2 needs exactly 3"});
  require_error([p = put("q.txt", "1 2 inf\n")] { read_points(p); }, {"q.txt:1:", "not finite"});
}

TEST_CASE("unknown extensions name the file", "[io][hostile]") {
  require_error(surface(put("x.foo", "v 0 0 0\n")), {"x.foo", "unknown surface extension"});
  require_error(tet(put("x.bar", "")), {"x.bar", "unknown tet mesh extension"});
}

// Every reader, the same hostile paths and bytes: a missing file, a folder, a pipe (which would block a
// naive reader forever), an empty file, binary garbage, a NUL in the middle, a lone huge number and a
// file cut off after one byte. Each must give a dfm::Error naming the file (and never hang or crash);
// the one exception is an empty points file, which is a valid list of 0 points.
TEST_CASE("every reader: missing, folder, pipe, empty, garbage, NUL, huge number, one byte", "[io][hostile]") {
  struct Reader {
    const char* ext;
    std::function<void(const std::string&)> read;
    std::string valid;  // a small valid file (the scene: its start), cut to one byte / NUL-patched below
  };
  const std::vector<Reader> readers = {
      {"obj", [](const std::string& p) { read_surface(p); }, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"},
      {"off", [](const std::string& p) { read_surface(p); }, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"},
      {"ply", [](const std::string& p) { read_surface(p); },
       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
       "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"},
      {"stl", [](const std::string& p) { read_surface(p); },
       "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid\n"},
      {"mesh", [](const std::string& p) { read_tet_mesh(p); },
       "MeshVersionFormatted 1\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\nTetrahedra\n1\n1 2 3 4 0\nEnd\n"},
      {"node", [](const std::string& p) { read_tet_mesh(p); }, "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n"},
      {"dmat", [](const std::string& p) { read_dmat(p); }, "1 2\n1\n2\n"},
      {"tgf", [](const std::string& p) { read_tgf(p); }, "1 0 0 0\n2 1 0 0\n#\n1 2\n"},
      {"xyz", [](const std::string& p) { read_points(p); }, "1 2 3\n"},
      {"scene.json", [](const std::string& p) { read_scene(p); }, "{\"format\": \"deform-scene\", \"version\": 1}"},
  };
  const std::string garbage("\x89PNG\r\n\x1a\n\0\0\0\rIHDR\xff\xfe\xfd\x00\x01", 21);
  int cases = 0;
  for (const Reader& r : readers) {
    const std::string e = r.ext;
    INFO(e);
    require_error([&] { r.read((dir() / ("missing." + e)).string()); }, {"missing." + e, "no such file"});
    fs::create_directories(dir() / ("folder." + e));
    require_error([&] { r.read((dir() / ("folder." + e)).string()); }, {"folder." + e, "directory"});
    const fs::path fifo = dir() / ("fifo." + e);
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    require_error([&] { r.read(fifo.string()); }, {"fifo." + e, "pipe"});
    if (e == "xyz")  // an empty points file is 0 points (a rig without point handles saves one)
      CHECK(read_points(put("hempty.xyz", "")).rows() == 0);
    else
      require_error([&] { r.read(put("hempty." + e, "")); }, {"hempty." + e});
    require_error([&] { r.read(put("garbage." + e, garbage)); }, {"garbage." + e});
    std::string nul = r.valid;
    nul[nul.size() / 2] = '\0';
    require_error([&] { r.read(put("nul." + e, nul)); }, {"nul." + e});
    require_error([&] { r.read(put("bignum." + e, "1e999999 99999999999999999999 -1\n")); }, {"bignum." + e});
    require_error([&] { r.read(put("onebyte." + e, r.valid.substr(0, 1))); }, {"onebyte." + e});
    cases += 8;
  }
  CHECK(cases == 80);
}

// Scene files (the JSON; tests/test_scene_file.cpp has the format's own cases): shapes, self-joined
// pseudo-edges and a sidecar that is a folder or a pipe.
TEST_CASE("scene: wrong empty shapes, self pseudo-edge, sidecar not a regular file", "[io][hostile][scene]") {
  const fs::path d = dir() / "scene";
  fs::create_directories(d);
  const std::string good = (d / "good.scene.json").string();
  write_scene(good, fuzz::fixed_scene());
  REQUIRE(read_scene(good).rig.points.size() == 2);
  std::ifstream in(good);
  const nlohmann::json j0 = nlohmann::json::parse(in);
  auto edited = [&](const std::string& name, const std::function<void(nlohmann::json&)>& f) {
    nlohmann::json j = j0;
    f(j);
    std::ofstream((d / name).string()) << j.dump(1);
    return (d / name).string();
  };
  auto scene = [](const std::string& p) { return [p] { read_scene(p); }; };
  // A 0 x 5 surface would pass for "empty" while every consumer assumes 3 columns.
  require_error(scene(edited("shape.scene.json", [](nlohmann::json& j) {
                  j["surface"]["N"]["rows"] = 0;
                  j["surface"]["N"]["cols"] = 5;
                })),
                {"shape.scene.json", "'surface.N' has 5 columns, expected 3"});
  require_error(scene(edited("self.scene.json", [](nlohmann::json& j) { j["rig"]["pseudo_edges"][0] = {1, 1}; })),
                {"self.scene.json", "joins a point to itself"});
  require_error(scene(edited("big.scene.json", [](nlohmann::json& j) { j["bind_stats"]["tets"] = 2147483648ll; })),
                {"big.scene.json", "'bind_stats.tets' = 2147483648 is out of range"});
  // The sidecar named by the JSON is a folder, then a pipe (opening a pipe would block forever).
  fs::create_directories(d / "folder.bin");
  require_error(scene(edited("dirbin.scene.json", [](nlohmann::json& j) { j["sidecar"]["file"] = "folder.bin"; })),
                {"folder.bin", "not a regular file"});
  REQUIRE(::mkfifo((d / "pipe.bin").c_str(), 0600) == 0);
  require_error(scene(edited("pipebin.scene.json", [](nlohmann::json& j) { j["sidecar"]["file"] = "pipe.bin"; })),
                {"pipe.bin", "not a regular file"});
}
