// Runs the real editor binary under the suite's X server: --screenshot writes a PNG showing a lit
// mesh; without a display the editor exits 1 naming xvfb-run; a script drives the document.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <sstream>
#include <string>

#include <catch2/catch.hpp>

#include "render/screenshot.h"
#include "tests/test_support.h"
#include "tests/volume_test_meshes.h"

namespace fs = std::filesystem;

namespace {

struct Run {
  int code = -1;
  std::string output;
};

Run run(const std::string& cmd) {
  Run r;
  std::FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  if (!p) return r;
  char buf[512];
  while (std::fgets(buf, sizeof buf, p)) r.output += buf;
  const int status = pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

std::string tmp(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("dfm_editor_test_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return (d / name).string();
}

// The mesh as an OBJ file with x scaled by sx (this test links no mesh writer).
void write_obj_stretched(const std::string& path, const dfm::TriMesh& m, double sx) {
  std::ofstream o(path);
  o.precision(17);
  for (int i = 0; i < m.V.rows(); ++i) o << "v " << sx * m.V(i, 0) << " " << m.V(i, 1) << " " << m.V(i, 2) << "\n";
  for (int f = 0; f < m.F.rows(); ++f) o << "f " << m.F(f, 0) + 1 << " " << m.F(f, 1) + 1 << " " << m.F(f, 2) + 1 << "\n";
}

// Statistics of the 3D viewport (the window minus the panels): the fraction of pixels that are the
// warm lit mesh, and the spread of their brightness (shading varies across a lit surface).
struct Coverage {
  double fraction = 0;
  double luminance_stddev = 0;
};

Coverage mesh_coverage(const dfm::gl::Image& img) {
  const int x0 = 260, x1 = img.width - 310, y0 = 40, y1 = img.height - 128;
  long n = 0, mesh = 0;
  double sum = 0, sum2 = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const unsigned char* p = &img.rgba[(size_t(y) * img.width + x) * 4];
      ++n;
      // The background and grid are blue-grey; the default material is warm (red > blue).
      if (int(p[0]) - int(p[2]) > 8 && p[0] > 45) {
        ++mesh;
        const double l = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
        sum += l;
        sum2 += l * l;
      }
    }
  Coverage c;
  c.fraction = n ? double(mesh) / n : 0;
  if (mesh > 1) c.luminance_stddev = std::sqrt(std::max(0.0, sum2 / mesh - (sum / mesh) * (sum / mesh)));
  return c;
}

}  // namespace

TEST_CASE("editor --screenshot renders a lit mesh and exits", "[editor][gl]") {
  DFM_DATA_OR_SKIP(knight, "decimated-knight.off");
  const std::string png = tmp("knight.png");
  const Run r = run(std::string("\"") + DFM_EDITOR_EXE + "\" \"" + knight + "\" --screenshot \"" + png + "\" --quit");
  INFO(r.output);
  REQUIRE(r.code == 0);
  const dfm::gl::Image img = dfm::gl::read_png(png);
  REQUIRE(img.width == 1280);
  REQUIRE(img.height == 800);
  const Coverage c = mesh_coverage(img);
  INFO("mesh fraction " << c.fraction << ", luminance stddev " << c.luminance_stddev);
  REQUIRE(c.fraction > 0.05);   // framed: the mesh fills a good part of the view
  REQUIRE(c.fraction < 0.9);    // ...but is not everything
  REQUIRE(c.luminance_stddev > 8.0);  // lit: shading varies
}

// CPU time (user + system, seconds) a process has used so far, from /proc/PID/stat.
double cpu_seconds(pid_t pid) {
  std::ifstream f("/proc/" + std::to_string(pid) + "/stat");
  std::string stat((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  const size_t close = stat.rfind(')');  // the command name may hold spaces
  if (close == std::string::npos) return -1;
  std::istringstream rest(stat.substr(close + 2));
  std::string field;
  double utime = 0, stime = 0;
  for (int i = 3; i <= 15 && rest >> field; ++i) {  // fields 14 and 15: utime, stime (clock ticks)
    if (i == 14) utime = std::stod(field);
    if (i == 15) stime = std::stod(field);
  }
  return (utime + stime) / static_cast<double>(::sysconf(_SC_CLK_TCK));
}

// An idle interactive editor (no input, no job, not playing) sleeps in glfwWaitEventsTimeout: it
// used more than a whole core (1.66 cores on llvmpipe) redrawing as fast as it could.
TEST_CASE("an idle editor window sleeps", "[editor][gl]") {
  DFM_DATA_OR_SKIP(knight, "decimated-knight.off");
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1), ::dup2(null, 2);
    ::execl(DFM_EDITOR_EXE, DFM_EDITOR_EXE, knight.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  REQUIRE(pid > 0);
  ::sleep(5);  // start-up: context, shaders, the first frames
  const double c0 = cpu_seconds(pid);
  ::sleep(4);
  const double c1 = cpu_seconds(pid);
  ::kill(pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
  INFO("idle editor: " << c1 - c0 << " s of CPU in 4 s");
  REQUIRE(c0 >= 0);
  REQUIRE(c1 - c0 < 0.2 * 4);  // under 20% of one core (measured: 0%)
}

TEST_CASE("editor without a display exits 1 and names xvfb-run", "[editor][gl]") {
  const Run r = run(std::string("env -u DISPLAY -u WAYLAND_DISPLAY \"") + DFM_EDITOR_EXE + "\" --quit");
  REQUIRE(r.code == 1);
  REQUIRE(r.output.find("xvfb-run") != std::string::npos);
}

TEST_CASE("editor rejects unknown options with exit 2", "[editor]") {
  const Run r = run(std::string("\"") + DFM_EDITOR_EXE + "\" --bogus");
  REQUIRE(r.code == 2);
  REQUIRE(r.output.find("unknown option") != std::string::npos);
}

TEST_CASE("editor runs from any working directory and reports a missing file", "[editor][gl]") {
  const Run r = run("cd / && \"" + std::string(DFM_EDITOR_EXE) + "\" /nonexistent/mesh.obj --quit");
  REQUIRE(r.code == 1);
  REQUIRE(r.output.find("/nonexistent/mesh.obj") != std::string::npos);
}

TEST_CASE("a script on the default scene binds, poses, keys, scrubs and saves", "[editor][gl]") {
  const std::string posed = tmp("posed.obj"), shot = tmp("scrub.png"), script = tmp("accept.txt");
  {
    std::ofstream s(script);
    s << "bind\nset-key 0\nselect 5\nrotate 40 0 0 1\nselect 6\nrotate -40 0 0 1\nset-key 1\n"
         "select 5\nrotate -60 0 0 1\nselect 0\ntranslate 0 0.15 0\nset-key 2\nset-time 1.5\n"
      << "save-posed " << posed << "\nscreenshot " << shot << "\n";
  }
  const Run r = run(std::string("\"") + DFM_EDITOR_EXE + "\" --script \"" + script + "\" --quit");
  INFO(r.output);
  REQUIRE(r.code == 0);
  REQUIRE(fs::file_size(posed) > 1000);
  // The bind's wall time, and the HUD's figures as measured (not "0 fps 0.0 ms" in scripts).
  std::smatch m;
  REQUIRE(std::regex_search(r.output, m, std::regex("bind: wall time ([0-9.]+) s")));
  CHECK(std::stod(m[1]) > 0.0);
  REQUIRE(std::regex_search(r.output, m, std::regex("screenshot: .*scrub\\.png \\(HUD: ([0-9]+) fps  ([0-9.]+) ms")));
  CHECK(std::stoi(m[1]) > 0);
  CHECK(std::stod(m[2]) > 0.0);
  const Coverage c = mesh_coverage(dfm::gl::read_png(shot));
  INFO("mesh fraction " << c.fraction);
  REQUIRE(c.fraction > 0.05);
  REQUIRE(c.luminance_stddev > 8.0);
}

TEST_CASE("a failing script line exits 1 naming the script and line", "[editor][gl]") {
  const std::string script = tmp("bad.txt");
  {
    std::ofstream s(script);
    s << "select 0\nrotate 30 0 0\n";  // rotate needs 4 numbers
  }
  const Run r = run(std::string("\"") + DFM_EDITOR_EXE + "\" --script \"" + script + "\" --quit");
  REQUIRE(r.code == 1);
  REQUIRE(r.output.find("bad.txt:2") != std::string::npos);
}

// Regression: a time one double-ulp past a key or baked layer (as playback's accumulated dt gives)
// rounds to the layer's float on the GPU while the slab was picked in double: the slice was empty and
// the viewport showed no mesh. Also: frames stay drawn while the bind runs, and File > Export glTF's
// script twin writes a GLB with the asked influence count and reports the pruning error.
TEST_CASE("scrubbing onto a layer time shows the mesh; playback never shows an empty frame", "[editor][gl]") {
  const std::string a = tmp("key_ulp.png"), b = tmp("layer_ulp.png"), glb = tmp("scene.glb"), script = tmp("ulp.txt");
  {
    std::ofstream s(script);
    s << "bind\nset-key 0\nselect 5\nrotate 40 0 0 1\nset-key 1\nselect 5\nrotate -60 0 0 1\nset-key 2\n"
      << "set-time 1.0000000000000002\nscreenshot " << a << "\n"
      << "set-time 1.6000000000000003\nscreenshot " << b << "\n"
      << "export-gltf " << glb << " 8\nset-time 0\n";
  }
  const Run r = run(std::string("\"") + DFM_EDITOR_EXE + "\" --script \"" + script + "\" --play-frames 40 --quit");
  INFO(r.output);
  REQUIRE(r.code == 0);
  for (const std::string& png : {a, b}) {
    const Coverage c = mesh_coverage(dfm::gl::read_png(png));
    INFO(png << ": mesh fraction " << c.fraction);
    REQUIRE(c.fraction > 0.05);
  }
  // 40 frames at 1/30 s from t = 0 cross the layers at 0.2, 0.4, ... and the key at 1.
  REQUIRE(r.output.find("play-frames: 40 frames") != std::string::npos);
  REQUIRE(r.output.find("showed no vertices") == std::string::npos);
  REQUIRE(r.output.find(" 0 vertices shown") == std::string::npos);
  REQUIRE(r.output.find("frames drawn while binding") != std::string::npos);
  // The GLB header, and the report naming the influence count and the pruning error.
  std::ifstream f(glb, std::ios::binary);
  char magic[4] = {0, 0, 0, 0};
  f.read(magic, 4);
  REQUIRE(std::string(magic, 4) == "glTF");
  REQUIRE(r.output.find("8 influences") != std::string::npos);
  REQUIRE(r.output.find("pruning error") != std::string::npos);
}

// --drag-frames (issue 35: "a drag redraws at the rate of plain posing"): three keys of one sphere (the
// middle one stretched along x), a space-time edit at t = 1, then the benchmark drags it: every frame
// shows the edited slice and the figures come out with the posed baseline's.
TEST_CASE("--drag-frames drags the last space-time edit and prints frame times against posing", "[editor][gl]") {
  const dfm::TriMesh sphere = dfm::test::icosphere(Eigen::Vector3d::Zero(), 0.6, 3);
  const std::string a = tmp("drag_sphere.obj"), b = tmp("drag_wide.obj"), script = tmp("drag.txt");
  for (const auto& [path, sx] : {std::pair<std::string, double>{a, 1.0}, {b, 1.5}})
    write_obj_stretched(path, sphere, sx);
  {
    std::ofstream s(script);
    s << "key-mesh " << a << " 0\nkey-mesh " << b << " 1\nkey-mesh " << a << " 2\nset-time 1\n"
      << "edit-region 0 0.6 0 0.4 0 2\nedit-drag 0 0.6 0 0 0.1 0\n";
  }
  const Run r = run(std::string("\"") + DFM_EDITOR_EXE + "\" \"" + a + "\" --script \"" + script + "\" --drag-frames 12 --quit");
  INFO(r.output);
  REQUIRE(r.code == 0);
  REQUIRE(r.output.find("drag-frames: 12 frames (12 showed the edited slice)") != std::string::npos);
  REQUIRE(r.output.find("drag-frames: the edited slice redrawn still: mean ") != std::string::npos);
  std::smatch m;
  REQUIRE(std::regex_search(r.output, m, std::regex("drag-frames: drag mean ([0-9.]+) ms; posed mean ([0-9.]+) ms; ratio ([0-9.]+)")));
  CHECK(std::stod(m[1]) > 0.0);
  CHECK(std::stod(m[2]) > 0.0);
}

// The Shape space panel (Alexa 2002, ch. 5) over two mesh keys, a sphere at t = 0 and the sphere
// stretched 1.8x along x at t = 1: with the cursor on a base's own pad point the viewport shows that
// base (the HUD says "shape space"), so the stretched one covers more of the view than the sphere.
// Halfway, as rigid as possible, the shape is synthesized on the panel's worker thread and the script's
// screenshot waits for it: it lies between the two.
TEST_CASE("the Shape space panel shows the shape at the pad's cursor in the viewport", "[editor][gl]") {
  const dfm::TriMesh sphere = dfm::test::icosphere(Eigen::Vector3d::Zero(), 0.6, 2);
  const std::string a = tmp("ss_sphere.obj"), b = tmp("ss_wide.obj"), script = tmp("ss.txt");
  for (const auto& [path, sx] : {std::pair<std::string, double>{a, 1.0}, {b, 1.8}})
    write_obj_stretched(path, sphere, sx);
  double fraction[3];
  for (int run_i = 0; run_i < 3; ++run_i) {
    const std::string png = tmp("ss" + std::to_string(run_i) + ".png");
    {
      std::ofstream s(script);
      s << "key-mesh " << a << " 0\nkey-mesh " << b << " 1\nscreenshot " << png << "\n";
    }
    // Two bases sit at (0.15, 0.5) and (0.85, 0.5) on the pad; the cursor on one of them, or halfway.
    const char* cursor[3] = {"0.15:0.5", "0.85:0.5", "0.5:0.5,shape_morph=arap"};
    const Run r = run(std::string("\"") + DFM_EDITOR_EXE + "\" \"" + a + "\" --ui shape_space=0:1,shape_cursor=" +
                      cursor[run_i] + " --script \"" + script + "\" --quit");
    INFO(r.output);
    REQUIRE(r.code == 0);
    REQUIRE(r.output.find("shape space)") != std::string::npos);
    if (run_i == 2) {
      REQUIRE(r.output.find("shape space: the ARAP shape at the cursor (") != std::string::npos);
    }
    fraction[run_i] = mesh_coverage(dfm::gl::read_png(png)).fraction;
  }
  INFO("mesh fraction: sphere " << fraction[0] << ", stretched " << fraction[1] << ", halfway (ARAP) " << fraction[2]);
  CHECK(fraction[0] > 0.02);
  CHECK(fraction[1] > 1.4 * fraction[0]);
  CHECK(fraction[2] > fraction[0] + 0.2 * (fraction[1] - fraction[0]));
  CHECK(fraction[2] < fraction[1] - 0.2 * (fraction[1] - fraction[0]));
}

TEST_CASE("editor options: --msaa takes 0..8", "[editor]") {
  const Run r = run(std::string("\"") + DFM_EDITOR_EXE + "\" --msaa 3x --quit");
  REQUIRE(r.code == 2);
  REQUIRE(r.output.find("--msaa") != std::string::npos);
}
