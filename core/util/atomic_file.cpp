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
  std::ifstream in(path, std::ios::binary);
  if (!in) throw file_error(path, 0, std::string("cannot open for reading: ") + std::strerror(errno));
}

void write_file_atomic(const std::string& path, const std::function<void(std::ostream&)>& write,
                       bool binary) {
  if (path.empty()) throw Error("empty output file name");
  fs::path target(path);
  std::error_code ec;
  if (fs::is_directory(target, ec)) throw file_error(path, 0, "is a directory, cannot write a file there");
  fs::path dir = target.parent_path();
  if (dir.empty()) dir = ".";
  std::random_device rd;
  fs::path tmp = dir / ("." + target.filename().string() + ".tmp" + std::to_string(rd() % 1000000));
  {
    std::ofstream out(tmp, binary ? std::ios::binary | std::ios::out : std::ios::out);
    if (!out) throw file_error(path, 0, std::string("cannot create temporary file: ") + std::strerror(errno));
    try {
      write(out);
    } catch (...) {
      out.close();
      fs::remove(tmp, ec);
      throw;
    }
    out.flush();
    if (!out) {
      out.close();
      fs::remove(tmp, ec);
      throw file_error(path, 0, "write failed (disk full?); previous file left untouched");
    }
  }
  fs::rename(tmp, target, ec);
  if (ec) {
    std::error_code ec2;
    fs::remove(tmp, ec2);
    throw file_error(path, 0, "cannot replace file: " + ec.message() + "; previous file left untouched");
  }
}

}  // namespace dfm
