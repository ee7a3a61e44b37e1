// The command table (core/scene/command.h): a script line and a UI call (the same entry, typed
// arguments) give the same document; every command is documented in SCRIPT.md and every documented
// command is in the table; the undo flag says what the document does; poll greys out what cannot run.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <unistd.h>

#include "core/scene/command.h"
#include "core/scene/script.h"
#include "core/util/error.h"
#include "tests/volume_test_meshes.h"

using namespace dfm;
namespace fs = std::filesystem;

namespace {

TriMesh unit_box() { return test::box_mesh(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones()); }

// Two point handles and a bone in a unit box, weights fixed by hand (rows sum to 1).
void make_posable(Document& d) {
  d.set_surface(unit_box(), "box");
  d.add_point({0.1, 0.1, 0.1});
  d.add_point({0.2, 0.1, 0.1});
  d.add_bone_chain({{0, 0, 0.2}, {0.1, 0, 0.2}});
  d.rename_handle(2, "l_arm");
  Eigen::MatrixXd W(8, 3);
  for (int i = 0; i < 8; ++i) W.row(i) << 0.1 * i, 0.3, 0.7 - 0.1 * i;
  W(7, 0) = 0.65, W(7, 2) = 0.05;
  d.set_weights(W, {});
}

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The saved scene (JSON and binary sidecar) as one string: the whole document's state.
std::string saved(Document& d, const fs::path& dir, const std::string& name) {
  const fs::path f = dir / (name + ".scene.json");
  d.save_scene(f.string());
  std::string all = read_file(f);
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().rfind(name + ".scene.", 0) == 0 && e.path() != f) all += read_file(e.path());
  // The file names differ by design; the rest must not.
  return std::regex_replace(all, std::regex(name + "\\.scene"), "X.scene");
}

struct TempDir {
  fs::path dir = fs::temp_directory_path() / ("dfm_commands_test_" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(dir); }
  ~TempDir() { fs::remove_all(dir); }
};

}  // namespace

TEST_CASE("a script line and a UI call of the same table entry give the same document") {
  TempDir tmp;
  Document by_script, by_ui;
  make_posable(by_script);
  make_posable(by_ui);
  run_script(by_script,
             parse_script("select l_arm\n"  // by name
                          "rotate 60 0 0 1\n"
                          "set-key 0\n"
                          "select 0\n"
                          "translate 0.1 -0.2 0.30000000000000004\n"
                          "set-key 1.5\n"
                          "set-inbetween 0 linear\n"
                          "set-time 0.75\n"
                          "weights-limit 2 0\n"
                          "set-method dqs\n",
                          "s.txt"),
             "s.txt", ScriptHost{});
  // As the editor's buttons call it: typed values, handles by number.
  run_command(by_ui, command_words("select", {2}));
  run_command(by_ui, command_words("rotate", {60.0, 0.0, 0.0, 1.0}));
  run_command(by_ui, command_words("set-key", {0.0}));
  run_command(by_ui, command_words("select", {0}));
  run_command(by_ui, command_words("translate", {0.1, -0.2, 0.1 + 0.2}));
  run_command(by_ui, command_words("set-key", {1.5}));
  run_command(by_ui, command_words("set-inbetween", {0.0, "linear"}));
  run_command(by_ui, command_words("set-time", {0.75}));
  run_command(by_ui, command_words("weights-limit", {2, 0.0}));
  run_command(by_ui, command_words("set-method", {"dqs"}));
  CHECK(by_script.undo_depth() == by_ui.undo_depth());
  CHECK(by_script.time() == by_ui.time());
  CHECK(by_script.weights() == by_ui.weights());
  REQUIRE(by_ui.keys().size() == 2);
  CHECK(by_ui.keys()[1].params.point_translation[0] == Eigen::Vector3d(0.1, -0.2, 0.1 + 0.2));
  CHECK(saved(by_script, tmp.dir, "a") == saved(by_ui, tmp.dir, "b"));
  // Undone the same way, step by step.
  while (by_ui.can_undo()) {
    run_command(by_ui, {"undo"});
    run_script(by_script, parse_script("undo\n", "u.txt"), "u.txt");
    CHECK(saved(by_script, tmp.dir, "a") == saved(by_ui, tmp.dir, "b"));
  }
}

TEST_CASE("a UI call is checked as a script line is, and its errors name the command") {
  Document d;
  make_posable(d);
  CHECK_THROWS_WITH(run_command(d, {"rotate", "x", "0", "0", "1"}), Catch::StartsWith("rotate: 'x' is not a finite number"));
  CHECK_THROWS_WITH(run_command(d, {"fly"}), Catch::Contains("unknown command 'fly'"));
  CHECK_THROWS_WITH(run_command(d, command_words("add-point", {1.0, 2.0})), Catch::Contains("takes 3 argument(s), got 2"));
  CHECK_THROWS_WITH(run_command(d, command_words("select", {7})), Catch::StartsWith("select: no handle 7"));
  CHECK(d.rig().points.size() == 2);  // nothing ran
  // A number reads back as the same double, to the last bit.
  for (double x : {0.1, 1.0 / 3.0, -2.5e-300, 123456.789})
    CHECK(std::strtod(CommandArg(x).word.c_str(), nullptr) == x);
}

TEST_CASE("every command is in SCRIPT.md's table and every row there is a command") {
  const std::string doc = read_file(fs::path(DFM_SOURCE_DIR) / "core/scene/SCRIPT.md");
  std::set<std::string> documented;
  const std::regex row("\\n\\| `([a-z-]+)`( / `([a-z-]+)`)? \\|");
  for (auto it = std::sregex_iterator(doc.begin(), doc.end(), row); it != std::sregex_iterator(); ++it) {
    documented.insert((*it)[1]);
    if ((*it)[3].matched) documented.insert((*it)[3]);
  }
  std::set<std::string> table;
  for (const Command& c : commands()) table.insert(c.name);
  CHECK(documented == table);
  for (const Command& c : commands()) {
    INFO(c.name);
    CHECK(c.usage.rfind(c.name, 0) == 0);  // usage starts with the name
    CHECK(c.min_args <= c.max_args);
    CHECK((c.max_args == 0 || !c.args.empty()));  // arguments have kinds
    CHECK(find_command(c.name) == &c);            // one entry per name
  }
}

TEST_CASE("a command's undo flag says whether it adds an undo step") {
  // {what runs first, the line measured}; lines that change the document (a weight tool that changes
  // nothing adds no step: test_weight_tools_document).
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"", "add-point 0 0 0"}, {"", "select 0"}, {"select 0", "translate 0 0 0.1"}, {"select 2", "rotate 10 0 0 1"},
      {"", "set-method dqs"}, {"", "set-key 0"}, {"", "set-time 1"}, {"set-time 2", "set-key"},
      {"set-key 0\nset-key 1", "set-inbetween 0 linear"}, {"set-key 1", "delete-key 1"}, {"", "reset-pose"},
      {"", "fast on 3"}, {"", "handle-state 0 free"}, {"", "bind-monotone on"}, {"", "ik-chain 2"},
      {"", "pseudo-edge 0 1"}, {"", "paint-mask 0 0 0 0.5 1"}, {"", "paint-dab 0 0 0 0.5 0.5 0.5"},
      {"", "weights-limit 2"}, {"", "weights-smooth"}, {"", "weights-report"}, {"add-point 1 1 1", "undo"}, {"add-point 1 1 1\nundo", "redo"}};
  for (const auto& [setup, line] : cases) {
    Document d;
    make_posable(d);
    ScriptHost host;
    host.print = [](const std::string&) {};
    run_script(d, parse_script(setup + "\n", "s.txt"), "s.txt", host);
    const auto parsed = parse_script(line + "\n", "s.txt");
    const Command& c = *find_command(parsed[0].words[0]);
    const int before = d.undo_depth();
    run_script(d, parsed, "s.txt", host);
    INFO(line);
    if (c.name == "undo") CHECK(d.undo_depth() == before - 1);  // not a step of its own
    else if (c.name == "redo") CHECK(d.undo_depth() == before + 1);
    else CHECK(d.undo_depth() - before == (c.undoable ? 1 : 0));
  }
}

TEST_CASE("poll greys out what cannot run, and says why") {
  Document empty;
  CHECK_THAT(command_unavailable("bind", empty), Catch::Contains("no surface"));
  CHECK_THAT(command_unavailable("replace-surface", empty), Catch::Contains("no surface"));
  CHECK(command_unavailable("open", empty).empty());
  Document d;
  d.set_surface(unit_box(), "box");
  CHECK_THAT(command_unavailable("bind", d), Catch::Contains("no handles"));
  d.add_point({0.1, 0.1, 0.1});
  CHECK(command_unavailable("bind", d).empty());
  CHECK_THAT(command_unavailable("weights-limit", d), Catch::Contains("bind first"));
  CHECK_THAT(command_unavailable("export-gltf", d), Catch::Contains("bind first"));
  CHECK_THAT(command_unavailable("translate", empty), Catch::Contains("no handle selected"));
  CHECK(command_unavailable("undo", d).empty());
  Document posable;
  make_posable(posable);
  CHECK(command_unavailable("weights-limit", posable).empty());
  CHECK(command_unavailable("save-posed", posable).empty());
  CHECK_THAT(command_unavailable("save-frames", posable), Catch::Contains("two keys"));
  run_command(posable, command_words("set-key", {0.0}));
  run_command(posable, command_words("set-key", {1.0}));
  CHECK(command_unavailable("save-frames", posable).empty());
  CHECK_THAT(command_unavailable("fly", posable), Catch::Contains("unknown command"));
}
