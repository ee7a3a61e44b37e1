#include "core/bind/tetrahedralize.h"

#include <Eigen/Geometry>
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unordered_map>
#include <vector>

#include "core/util/error.h"

#ifndef DFM_TETGEN_EXE
#define DFM_TETGEN_EXE "tetgen"
#endif

extern char** environ;

namespace dfm {
namespace fs = std::filesystem;

namespace {

// A temporary folder removed when it goes out of scope, whatever happens.
struct TempDir {
  fs::path path;
  TempDir() {
    std::string tmpl = (fs::temp_directory_path() / "dfm-tetgen-XXXXXX").string();
    std::vector<char> buf(tmpl.begin(), tmpl.end());
    buf.push_back('\0');
    if (!mkdtemp(buf.data())) throw Error("cannot create a temporary folder for TetGen: " + std::string(std::strerror(errno)));
    path = buf.data();
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

std::string checked_switches(const std::string& sw, bool has_facets) {
  std::string out;
  bool skipping_number = false;
  for (char ch : sw) {
    if (skipping_number && (std::isdigit(static_cast<unsigned char>(ch)) || ch == '.' || ch == '/')) continue;
    skipping_number = false;
    if (ch == '-' && out.empty()) continue;  // tolerate a leading dash
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '.' || ch == '/'))
      throw Error("TetGen switches \"" + sw + "\": unexpected character '" + std::string(1, ch) + "'");
    // These change the output's shape or need extra input files.
    if (ch == 'z' || ch == 'F') continue;  // added below
    if (std::strchr("roNEIwimh", ch))
      throw Error("TetGen switches \"" + sw + "\": switch '" + std::string(1, ch) + "' is not supported here");
    // A point set has no PLC; TetGen 1.5.0 also deletes every tet of a point set refined with q or a.
    if (!has_facets && std::strchr("pYdqa", ch)) {
      skipping_number = true;
      continue;
    }
    out += ch;
  }
  // z: 0-based output. F: no .face/.edge files (never read here; writing them is a tenth of TetGen's time).
  return out + "zF";
}

bool executable_exists(const std::string& name) {
  if (name.find('/') != std::string::npos) return access(name.c_str(), X_OK) == 0;
  const char* path = std::getenv("PATH");
  std::stringstream ss(path ? path : "/usr/bin:/bin");
  for (std::string dir; std::getline(ss, dir, ':');)
    if (!dir.empty() && access((dir + "/" + name).c_str(), X_OK) == 0) return true;
  return false;
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The lines of TetGen's log that explain a failure (timings and banners removed).
std::string failure_message(const std::string& log) {
  std::vector<std::string> lines;
  std::stringstream ss(log);
  for (std::string l; std::getline(ss, l);) {
    if (l.empty() || l.find("seconds") != std::string::npos || l.find("terminate called") != std::string::npos)
      continue;
    lines.push_back(l);
  }
  std::string msg;
  size_t from = lines.size() > 6 ? lines.size() - 6 : 0;
  for (size_t i = from; i < lines.size(); ++i) msg += (msg.empty() ? "" : " | ") + lines[i];
  return msg.empty() ? "(no output)" : msg;
}

// Runs argv with stdout+stderr into log_path; returns the wait status.
int run_process(const std::vector<std::string>& args, const fs::path& log_path) {
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 1, log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  pid_t pid;
  int rc = posix_spawnp(&pid, argv[0], &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0) throw Error("cannot run TetGen (" + args[0] + "): " + std::strerror(rc));
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw Error("waiting for TetGen failed: " + std::string(std::strerror(errno)));
  }
  return status;
}

// Whitespace tokens of a TetGen file with '#' comments removed.
// The whitespace-separated tokens of a TetGen output file ('#' starts a comment), parsed in place from
// one buffer: armadillo's .ele alone has 1.5M tokens, and one std::string each cost more than TetGen's
// own output stage.
struct Tokens {
  std::string buf;
  std::vector<std::pair<uint32_t, uint32_t>> t;  // [begin, end) in buf
  size_t i = 0;
  std::string path;
  explicit Tokens(const fs::path& p) : path(p.string()) {
    std::ifstream in(p, std::ios::binary);
    if (!in) throw Error("TetGen produced no " + p.filename().string());
    std::ostringstream ss;
    ss << in.rdbuf();
    buf = ss.str();
    if (buf.size() >= 0xffffffffu) throw file_error(path, 0, "file too large");
    const uint32_t n = static_cast<uint32_t>(buf.size());
    for (uint32_t k = 0; k < n;) {
      const char c = buf[k];
      if (c == '#') {
        while (k < n && buf[k] != '\n') ++k;
      } else if (std::isspace(static_cast<unsigned char>(c))) {
        ++k;
      } else {
        const uint32_t b = k;
        while (k < n && buf[k] != '#' && !std::isspace(static_cast<unsigned char>(buf[k]))) ++k;
        t.emplace_back(b, k);
      }
    }
  }
  size_t size() const { return t.size(); }
  std::string text(size_t k) const { return buf.substr(t[k].first, t[k].second - t[k].first); }
  void next() {
    if (i >= t.size()) throw file_error(path, 0, "truncated TetGen output");
    ++i;
  }
  long integer() {
    next();
    const char* b = buf.c_str() + t[i - 1].first;
    char* end;
    const long v = std::strtol(b, &end, 10);
    if (end != buf.c_str() + t[i - 1].second) throw file_error(path, 0, "expected an integer, got \"" + text(i - 1) + "\"");
    return v;
  }
  double real() {
    next();
    const char* b = buf.c_str() + t[i - 1].first;
    char* end;
    const double v = std::strtod(b, &end);
    if (end != buf.c_str() + t[i - 1].second) throw file_error(path, 0, "expected a number, got \"" + text(i - 1) + "\"");
    return v;
  }
};

struct Key {
  double x, y, z;
  bool operator==(const Key& o) const { return x == o.x && y == o.y && z == o.z; }
};
struct KeyHash {
  size_t operator()(const Key& k) const {
    std::hash<double> h;
    return h(k.x) ^ (h(k.y) * 0x9e3779b97f4a7c15ull) ^ (h(k.z) * 0xc2b2ae3d27d4eb4full);
  }
};

}  // namespace

std::string tetgen_executable() {
  const char* env = std::getenv("DFM_TETGEN");
  return env && *env ? env : DFM_TETGEN_EXE;
}

TetgenResult tetrahedralize(const Plc& plc, const std::string& switches) {
  const auto t0 = std::chrono::steady_clock::now();
  const bool has_plc = plc.F.rows() > 0 || plc.E.rows() > 0;
  const std::string sw = checked_switches(switches, has_plc);
  const int nv = static_cast<int>(plc.V.rows());
  if (nv < 4) throw Error("tetrahedralize: need at least 4 points, got " + std::to_string(nv));
  for (int i = 0; i < nv; ++i)
    if (!plc.V.row(i).allFinite()) throw Error("tetrahedralize: point " + std::to_string(i) + " is not finite");
  auto check_index = [&](int v) {
    if (v < 0 || v >= nv) throw Error("tetrahedralize: facet/segment index " + std::to_string(v) + " out of range");
  };

  TempDir dir;
  const fs::path in = dir.path / (has_plc ? "in.poly" : "in.node");
  {
    FILE* f = std::fopen(in.c_str(), "w");
    if (!f) throw Error("cannot write " + in.string());
    std::fprintf(f, "%d 3 0 0\n", nv);
    for (int i = 0; i < nv; ++i) std::fprintf(f, "%d %.17g %.17g %.17g\n", i, plc.V(i, 0), plc.V(i, 1), plc.V(i, 2));
    if (has_plc) {
      std::fprintf(f, "%ld 0\n", static_cast<long>(plc.F.rows() + plc.E.rows()));
      for (int i = 0; i < plc.F.rows(); ++i) {
        for (int k = 0; k < 3; ++k) check_index(plc.F(i, k));
        std::fprintf(f, "1\n3 %d %d %d\n", plc.F(i, 0), plc.F(i, 1), plc.F(i, 2));
      }
      for (int i = 0; i < plc.E.rows(); ++i) {  // a two-vertex polygon is a segment
        for (int k = 0; k < 2; ++k) check_index(plc.E(i, k));
        std::fprintf(f, "1\n2 %d %d\n", plc.E(i, 0), plc.E(i, 1));
      }
      std::fprintf(f, "0\n0\n");
    }
    if (std::fclose(f) != 0) throw Error("cannot write " + in.string() + " (disk full?)");
  }

  const std::string exe = tetgen_executable();
  if (!executable_exists(exe)) throw Error("TetGen executable \"" + exe + "\" not found (install the Debian package tetgen)");
  std::vector<std::string> args;
  // TetGen reports errors with printf and then aborts: unbuffer it so the message reaches the log.
  if (executable_exists("stdbuf")) args = {"stdbuf", "-o0", "-e0"};
  args.push_back(exe);
  args.push_back("-" + sw);
  args.push_back(in.string());
  const fs::path log_path = dir.path / "log.txt";
  const int status = run_process(args, log_path);

  TetgenResult res;
  res.log = read_text(log_path);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::string how = WIFSIGNALED(status) ? "aborted (signal " + std::to_string(WTERMSIG(status)) + ")"
                                          : "exited with status " + std::to_string(WEXITSTATUS(status));
    throw Error("TetGen -" + sw + " failed, " + how + ": " + failure_message(res.log));
  }

  const fs::path stem = dir.path / "in.1";
  Tokens node(stem.string() + ".node");
  const long n = node.integer();
  const long dim = node.integer(), nattr = node.integer(), nmark = node.integer();
  if (n < 0 || dim != 3 || nattr < 0 || nmark < 0 || nmark > 1) throw file_error(node.path, 0, "unexpected header");
  if (static_cast<size_t>(n) * (4 + nattr + nmark) > node.size()) throw file_error(node.path, 0, "truncated");
  res.mesh.V.resize(n, 3);
  for (long i = 0; i < n; ++i) {
    const long id = node.integer();
    if (id != i) throw file_error(node.path, 0, "nodes out of order (expected " + std::to_string(i) + ")");
    for (int k = 0; k < 3; ++k) res.mesh.V(i, k) = node.real();
    for (long k = 0; k < nattr + nmark; ++k) node.next();
  }
  Tokens ele(stem.string() + ".ele");
  const long m = ele.integer(), per = ele.integer(), eattr = ele.integer();
  if (m < 0 || per != 4 || eattr < 0) throw file_error(ele.path, 0, "unexpected header (only linear tets)");
  if (static_cast<size_t>(m) * (5 + eattr) > ele.size()) throw file_error(ele.path, 0, "truncated");
  res.mesh.T.resize(m, 4);
  for (long i = 0; i < m; ++i) {
    ele.integer();
    for (int k = 0; k < 4; ++k) {
      long v = ele.integer();
      if (v < 0 || v >= n) throw file_error(ele.path, 0, "vertex index out of range");
      res.mesh.T(i, k) = static_cast<int>(v);
    }
    for (long k = 0; k < eattr; ++k) ele.next();
    // Orient positively: det[v1-v0, v2-v0, v3-v0] > 0.
    const Eigen::Vector3d p0 = res.mesh.V.row(res.mesh.T(i, 0));
    const Eigen::Vector3d e1 = res.mesh.V.row(res.mesh.T(i, 1)).transpose() - p0;
    const Eigen::Vector3d e2 = res.mesh.V.row(res.mesh.T(i, 2)).transpose() - p0;
    const Eigen::Vector3d e3 = res.mesh.V.row(res.mesh.T(i, 3)).transpose() - p0;
    if (e1.dot(e2.cross(e3)) < 0) std::swap(res.mesh.T(i, 1), res.mesh.T(i, 2));
  }

  // TetGen keeps input points first unless it drops some (duplicates, points outside the domain):
  // map input rows to output vertices by their exactly round-tripped coordinates.
  res.input_to_tet = Eigen::VectorXi::Constant(nv, -1);
  bool identity = n >= nv;
  for (int i = 0; identity && i < nv; ++i) identity = res.mesh.V.row(i) == plc.V.row(i);
  if (identity) {
    for (int i = 0; i < nv; ++i) res.input_to_tet(i) = i;
  } else {
    std::unordered_map<Key, int, KeyHash> where;
    for (int i = 0; i < n; ++i) where.emplace(Key{res.mesh.V(i, 0) + 0.0, res.mesh.V(i, 1) + 0.0, res.mesh.V(i, 2) + 0.0}, i);
    for (int i = 0; i < nv; ++i) {
      auto it = where.find(Key{plc.V(i, 0) + 0.0, plc.V(i, 1) + 0.0, plc.V(i, 2) + 0.0});
      if (it != where.end()) res.input_to_tet(i) = it->second;
    }
  }
  // A vertex no tet uses (TetGen -J keeps them) counts as dropped.
  std::vector<char> used(n, 0);
  for (long i = 0; i < m; ++i)
    for (int k = 0; k < 4; ++k) used[res.mesh.T(i, k)] = 1;
  for (int i = 0; i < nv; ++i)
    if (res.input_to_tet(i) >= 0 && !used[res.input_to_tet(i)]) res.input_to_tet(i) = -1;

  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

}  // namespace dfm
