#include "core/bind/tetrahedralize.h"

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

#include "core/mesh/io_formats.h"
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

// Refuses what TetGen cannot take: fewer than 4 points, a non-finite point, an index out of range.
void check_plc(const Plc& plc) {
  const int nv = static_cast<int>(plc.V.rows());
  if (nv < 4) throw Error("tetrahedralize: need at least 4 points, got " + std::to_string(nv));
  for (int i = 0; i < nv; ++i)
    if (!plc.V.row(i).allFinite()) throw Error("tetrahedralize: point " + std::to_string(i) + " is not finite");
  const auto in_range = [nv](const Eigen::MatrixXi& M) { return M.size() == 0 || (M.minCoeff() >= 0 && M.maxCoeff() < nv); };
  for (const Eigen::MatrixXi* M : {&plc.F, &plc.E})
    if (!in_range(*M))
      throw Error("tetrahedralize: facet/segment index " + std::to_string(M->minCoeff() < 0 ? M->minCoeff() : M->maxCoeff()) +
                  " out of range");
}

// TetGen's input: a .poly (points, facets, segments as two-vertex polygons) or, without facets, a .node.
void write_tetgen_input(const fs::path& in, const Plc& plc, bool has_plc) {
  FILE* f = std::fopen(in.c_str(), "w");
  if (!f) throw Error("cannot write " + in.string());
  const int nv = static_cast<int>(plc.V.rows());
  std::fprintf(f, "%d 3 0 0\n", nv);
  for (int i = 0; i < nv; ++i) std::fprintf(f, "%d %.17g %.17g %.17g\n", i, plc.V(i, 0), plc.V(i, 1), plc.V(i, 2));
  if (has_plc) {
    std::fprintf(f, "%ld 0\n", static_cast<long>(plc.F.rows() + plc.E.rows()));
    for (int i = 0; i < plc.F.rows(); ++i) std::fprintf(f, "1\n3 %d %d %d\n", plc.F(i, 0), plc.F(i, 1), plc.F(i, 2));
    for (int i = 0; i < plc.E.rows(); ++i) std::fprintf(f, "1\n2 %d %d\n", plc.E(i, 0), plc.E(i, 1));
    std::fprintf(f, "0\n0\n");
  }
  if (std::fclose(f) != 0) throw Error("cannot write " + in.string() + " (disk full?)");
}

// Runs TetGen -sw on `in`; returns its log. Throws with TetGen's last words when it fails.
std::string run_tetgen(const fs::path& in, const std::string& sw) {
  const std::string exe = tetgen_executable();
  if (!executable_exists(exe)) throw Error("TetGen executable \"" + exe + "\" not found (install the Debian package tetgen)");
  std::vector<std::string> args;
  // TetGen reports errors with printf and then aborts: unbuffer it so the message reaches the log.
  if (executable_exists("stdbuf")) args = {"stdbuf", "-o0", "-e0"};
  args.push_back(exe);
  args.push_back("-" + sw);
  args.push_back(in.string());
  const fs::path log_path = in.parent_path() / "log.txt";
  const int status = run_process(args, log_path);
  std::string log = read_text(log_path);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::string how = WIFSIGNALED(status) ? "aborted (signal " + std::to_string(WTERMSIG(status)) + ")"
                                          : "exited with status " + std::to_string(WEXITSTATUS(status));
    throw Error("TetGen -" + sw + " failed, " + how + ": " + failure_message(log));
  }
  return log;
}

// plc.V row -> output vertex, -1 where TetGen dropped it. TetGen keeps input points first unless it
// drops some (duplicates, points outside the domain): then match exactly round-tripped coordinates.
// A vertex no tet uses (TetGen -J keeps them) counts as dropped.
Eigen::VectorXi input_to_output(const Eigen::MatrixXd& input, const TetMesh& mesh) {
  const int nv = static_cast<int>(input.rows()), n = mesh.num_vertices();
  Eigen::VectorXi to = Eigen::VectorXi::Constant(nv, -1);
  bool identity = n >= nv;
  for (int i = 0; identity && i < nv; ++i) identity = mesh.V.row(i) == input.row(i);
  if (identity) {
    for (int i = 0; i < nv; ++i) to(i) = i;
  } else {
    std::unordered_map<Key, int, KeyHash> where;
    for (int i = 0; i < n; ++i) where.emplace(Key{mesh.V(i, 0) + 0.0, mesh.V(i, 1) + 0.0, mesh.V(i, 2) + 0.0}, i);
    for (int i = 0; i < nv; ++i) {
      auto it = where.find(Key{input(i, 0) + 0.0, input(i, 1) + 0.0, input(i, 2) + 0.0});
      if (it != where.end()) to(i) = it->second;
    }
  }
  std::vector<char> used(n, 0);
  for (long i = 0; i < mesh.T.rows(); ++i)
    for (int k = 0; k < 4; ++k) used[mesh.T(i, k)] = 1;
  for (int i = 0; i < nv; ++i)
    if (to(i) >= 0 && !used[to(i)]) to(i) = -1;
  return to;
}

}  // namespace

std::string tetgen_executable() {
  const char* env = std::getenv("DFM_TETGEN");
  return env && *env ? env : DFM_TETGEN_EXE;
}

TetgenResult tetrahedralize(const Plc& plc, const std::string& switches) {
  const auto t0 = std::chrono::steady_clock::now();
  const bool has_plc = plc.F.rows() > 0 || plc.E.rows() > 0;
  const std::string sw = checked_switches(switches, has_plc);
  check_plc(plc);
  TempDir dir;
  const fs::path in = dir.path / (has_plc ? "in.poly" : "in.node");
  write_tetgen_input(in, plc, has_plc);
  TetgenResult res;
  res.log = run_tetgen(in, sw);
  // TetGen's output, read by the mesh module's reader (which orients the tets positively).
  res.mesh = io::read_tetgen((dir.path / "in.1.node").string());
  res.input_to_tet = input_to_output(plc.V, res.mesh);
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

}  // namespace dfm
