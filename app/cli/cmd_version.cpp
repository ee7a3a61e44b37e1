// `deform version`: prints the program version.
#include <iostream>

#include "app/cli/command.h"

namespace {
int run(const dfm::cli::Args& args) {
  if (!args.empty()) throw dfm::cli::UsageError("version takes no arguments");
  std::cout << "deform 0.1.0\n";
  return 0;
}
dfm::cli::Register reg{"version", "print the version", "usage: deform version", &run};
}  // namespace
