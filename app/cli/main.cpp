// `deform`: command-line front end. Thin wrappers over core/ and render/.
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <iostream>

#include "app/cli/command.h"
#include "core/util/error.h"
#include "core/bind/numeric_setup.h"
#include "core/export/assimp_scene_import.h"
#include "core/export/gltf_scene_import.h"

namespace dfm::cli {

std::vector<Command>& registry() {
  static std::vector<Command> r;
  return r;
}

// A flag is "-x..." or "--x..." with a letter after the dashes; "-0.5" and "-3" are values.
static bool looks_like_flag(const std::string& s) {
  size_t i = 0;
  while (i < s.size() && i < 2 && s[i] == '-') ++i;
  return i > 0 && i < s.size() && std::isalpha(static_cast<unsigned char>(s[i]));
}

std::string ArgReader::value(const std::string& flag) {
  if (done() || looks_like_flag(peek())) throw UsageError(flag + " needs a value");
  return next();
}

double ArgReader::number(const std::string& flag) {
  std::string s = value(flag);
  char* end = nullptr;
  errno = 0;
  double v = std::strtod(s.c_str(), &end);
  if (end == s.c_str() || *end != '\0' || errno == ERANGE || !std::isfinite(v))
    throw UsageError(flag + " needs a finite number, got '" + s + "'");
  return v;
}

int ArgReader::integer(const std::string& flag) {
  std::string s = value(flag);
  char* end = nullptr;
  errno = 0;
  long v = std::strtol(s.c_str(), &end, 10);
  if (end == s.c_str() || *end != '\0' || errno == ERANGE || v < -1000000000L || v > 1000000000L)
    throw UsageError(flag + " needs an integer, got '" + s + "'");
  return static_cast<int>(v);
}

std::vector<std::string> ArgReader::values(const std::string& flag) {
  std::vector<std::string> out;
  while (!done() && !looks_like_flag(peek())) out.push_back(next());
  if (out.empty()) throw UsageError(flag + " needs at least one value");
  return out;
}

}  // namespace dfm::cli

namespace {

void print_help() {
  auto cmds = dfm::cli::registry();
  std::sort(cmds.begin(), cmds.end(), [](auto& a, auto& b) { return a.name < b.name; });
  std::cout << "deform: bind, pose and animate meshes from the command line.\n\n"
               "usage: deform <command> [options]\n       deform <command> --help\n\ncommands:\n";
  for (const auto& c : cmds) std::cout << "  " << c.name << std::string(c.name.size() < 10 ? 10 - c.name.size() : 1, ' ') << c.summary << "\n";
}

}  // namespace

// The process-wide numeric settings (core/bind/numeric_setup.h): serial OpenMP regions here,
// setup_numerics() first thing in main.
DFM_RUN_OPENMP_REGIONS_SERIALLY()

int main(int argc, char** argv) {
  dfm::setup_numerics();  // before any bind (numeric_setup.h)
  dfm::register_gltf_scene_importer();     // scripts' `open` reads rigged glTF as scenes
  dfm::register_assimp_scene_importers();  // ... FBX and Collada; load-motion reads BVH
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    print_help();
    return args.empty() ? 2 : 0;
  }
  const std::string name = args[0];
  for (const auto& c : dfm::cli::registry()) {
    if (c.name != name) continue;
    dfm::cli::Args rest(args.begin() + 1, args.end());
    if (std::find(rest.begin(), rest.end(), "--help") != rest.end() ||
        std::find(rest.begin(), rest.end(), "-h") != rest.end()) {
      std::cout << c.usage << "\n";
      return 0;
    }
    try {
      return c.run(rest);
    } catch (const dfm::cli::UsageError& e) {
      std::cerr << "deform " << name << ": " << e.what() << "\n\n" << c.usage << "\n";
      return 2;
    } catch (const dfm::Error& e) {
      std::cerr << "deform " << name << ": error: " << e.what() << "\n";
      return 1;
    } catch (const std::bad_alloc&) {
      std::cerr << "deform " << name << ": error: out of memory\n";
      return 1;
    } catch (const std::exception& e) {
      std::cerr << "deform " << name << ": error: " << e.what() << "\n";
      return 1;
    }
  }
  std::cerr << "deform: unknown command '" << name << "' (see deform --help)\n";
  return 2;
}
