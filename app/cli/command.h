#pragma once
// Subcommand registry for `deform`. Each cmd_*.cpp defines one subcommand and registers it with
//   static dfm::cli::Register reg{"name", "one-line summary", "usage text", &run};
// run() receives the arguments after the subcommand name and returns the exit code:
// 0 success, 1 bad input (file or data problem), 2 bad usage. It may throw dfm::Error (-> exit 1).
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace dfm::cli {

using Args = std::vector<std::string>;

struct Command {
  std::string name, summary, usage;
  std::function<int(const Args&)> run;
};

std::vector<Command>& registry();

struct Register {
  Register(std::string name, std::string summary, std::string usage, std::function<int(const Args&)> run) {
    registry().push_back({std::move(name), std::move(summary), std::move(usage), std::move(run)});
  }
};

// Thrown for bad usage (unknown flag, missing value): exit code 2 with the usage text.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Small helpers for flag parsing shared by subcommands.
class ArgReader {
 public:
  explicit ArgReader(const Args& args) : args_(args) {}
  bool done() const { return i_ >= args_.size(); }
  const std::string& peek() const { return args_[i_]; }
  std::string next() { return args_[i_++]; }
  // Value after a flag; throws UsageError if missing.
  std::string value(const std::string& flag);
  double number(const std::string& flag);
  int integer(const std::string& flag);
  // Values up to the next argument starting with "--".
  std::vector<std::string> values(const std::string& flag);

 private:
  const Args& args_;
  size_t i_ = 0;
};

}  // namespace dfm::cli
