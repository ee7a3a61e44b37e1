#pragma once
// Runs the `deform` executable as a child process (fork + execv: no shell, so no quoting issues),
// capturing exit status, stdout and stderr, and telling a normal exit from death by a signal.
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/scratch_dir.h"

namespace dfm::test {

struct RunResult {
  int exit_code = -1;    // valid when !signaled
  bool signaled = false;
  int signal = 0;
  std::string out, err;
  std::string command;   // for messages: the argument list, space separated
};

struct RunOptions {
  long max_file_bytes = -1;  // >= 0: RLIMIT_FSIZE in the child (a "full disk"); SIGXFSZ is ignored
};

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Runs exe with args; stdout/stderr go to files in scratch (a folder that exists).
inline RunResult run_program(const std::string& exe, const std::vector<std::string>& args,
                             const std::filesystem::path& scratch, const RunOptions& opt = {}) {
  RunResult r;
  r.command = exe;
  for (const auto& a : args) r.command += " '" + a + "'";
  const std::string out_path = (scratch / "child.stdout").string(), err_path = (scratch / "child.stderr").string();
  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(exe.c_str()));
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fo = ::open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int fe = ::open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int fi = ::open("/dev/null", O_RDONLY);
    if (fo < 0 || fe < 0 || fi < 0) ::_exit(127);
    ::dup2(fi, 0), ::dup2(fo, 1), ::dup2(fe, 2);
    if (opt.max_file_bytes >= 0) {
      ::signal(SIGXFSZ, SIG_IGN);  // writes past the limit then fail with EFBIG instead of killing
      rlimit lim{static_cast<rlim_t>(opt.max_file_bytes), static_cast<rlim_t>(opt.max_file_bytes)};
      ::setrlimit(RLIMIT_FSIZE, &lim);
    }
    ::execv(exe.c_str(), argv.data());
    ::_exit(127);
  }
  if (pid < 0) return r;
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
  }
  if (WIFSIGNALED(status)) {
    r.signaled = true;
    r.signal = WTERMSIG(status);
  } else if (WIFEXITED(status)) {
    r.exit_code = WEXITSTATUS(status);
  }
  r.out = slurp(out_path);
  r.err = slurp(err_path);
  return r;
}

#ifdef DEFORM_EXE
// `deform ARGS` run in a scratch folder (DEFORM_EXE: the tool, set by the CLI tests' CMake).
inline RunResult run_deform(const ScratchDir& s, const std::vector<std::string>& args, const RunOptions& o = {}) {
  return run_program(DEFORM_EXE, args, s.dir, o);
}
#endif

// The command, how it ended and the start of its output, for failure messages.
inline std::string describe_run(const RunResult& r, size_t out_chars = 3000) {
  return r.command + "\n  -> " + (r.signaled ? "signal " + std::to_string(r.signal) : "exit " + std::to_string(r.exit_code)) +
         "\n  stdout: " + r.out.substr(0, out_chars) + "\n  stderr: " + r.err.substr(0, 800);
}

}  // namespace dfm::test
