#include "core/util/atomic_file.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <system_error>
#include <unistd.h>

#include "core/util/error.h"

namespace dfm {
namespace fs = std::filesystem;

std::string file_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  if (!ext.empty() && ext[0] == '.') ext.erase(0, 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

void require_readable_file(const std::string& path) {
  std::error_code ec;
  if (path.empty()) throw Error("empty file name");
  auto st = fs::status(path, ec);
  if (ec || !fs::exists(st)) throw file_error(path, 0, "no such file");
  if (fs::is_directory(st)) throw file_error(path, 0, "is a directory, not a file");
  // Opening a pipe or socket would block until someone writes to it.
  if (fs::is_fifo(st) || fs::is_socket(st)) throw file_error(path, 0, "is a pipe or socket, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw file_error(path, 0, std::string("cannot open for reading: ") + std::strerror(errno));
}

namespace {

// Writes one file's temp beside it; returns the temp's path. On failure removes the temp and throws.
fs::path write_temp(const AtomicWrite& f) {
  const std::string& path = f.path;
  if (path.empty()) throw Error("empty output file name");
  const fs::path target(path);
  std::error_code ec;
  if (fs::is_directory(target, ec)) throw file_error(path, 0, "is a directory, cannot write a file there");
  fs::path dir = target.parent_path();
  if (dir.empty()) dir = ".";
  std::random_device rd;
  fs::path tmp;
  do {  // a name no other save is using
    tmp = dir / ("." + target.filename().string() + ".tmp" + std::to_string(rd() % 1000000));
  } while (fs::exists(fs::symlink_status(tmp, ec)));
  std::ofstream out(tmp, f.binary ? std::ios::binary | std::ios::out : std::ios::out);
  if (!out) throw file_error(path, 0, std::string("cannot create temporary file: ") + std::strerror(errno));
  try {
    f.write(out);
  } catch (...) {
    out.close();
    fs::remove(tmp, ec);
    throw;
  }
  // Failures of write, flush and close all show in the stream state (EFBIG, ENOSPC, EIO).
  out.flush();
  const int flush_errno = out ? 0 : errno;
  out.close();
  if (!out) {
    const int err = flush_errno ? flush_errno : errno;
    fs::remove(tmp, ec);
    throw file_error(path, 0, std::string("write failed (") + (err ? std::strerror(err) : "I/O error") +
                                  "); previous file left untouched");
  }
  // Keep the previous file's permissions (a private file stays private).
  const fs::file_status old = fs::status(target, ec);
  if (!ec && fs::is_regular_file(old)) fs::permissions(tmp, old.permissions(), ec);
  return tmp;
}

}  // namespace

void write_files_atomic(const std::vector<AtomicWrite>& files) {
  std::vector<fs::path> temps;
  std::error_code ec;
  auto drop_temps = [&](size_t from) {
    for (size_t i = from; i < temps.size(); ++i) fs::remove(temps[i], ec);
  };
  try {
    for (const AtomicWrite& f : files) temps.push_back(write_temp(f));
  } catch (...) {
    drop_temps(0);
    throw;
  }
  for (size_t i = 0; i < files.size(); ++i) {
    fs::rename(temps[i], files[i].path, ec);
    if (ec) {
      const std::string why = ec.message();
      drop_temps(i);
      throw file_error(files[i].path, 0, "cannot replace file: " + why + "; previous file left untouched");
    }
  }
}

void write_file_atomic(const std::string& path, const std::function<void(std::ostream&)>& write,
                       bool binary) {
  write_files_atomic({AtomicWrite{path, write, binary}});
}

}  // namespace dfm
