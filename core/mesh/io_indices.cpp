// Vertex index lists: one 0-based index per line; '#' comments and blank lines allowed.
#include "core/mesh/io.h"
#include "core/mesh/io_parse.h"

namespace dfm {

std::vector<int> read_vertex_indices(const std::string& path, int num_vertices) {
  std::string data = io::read_file(path);
  io::LineReader lr(data);
  std::string_view line;
  std::vector<std::string_view> t;
  std::vector<int> out;
  while (lr.next(line)) {
    io::split_ws(io::strip_comment(line), t);
    if (t.empty()) continue;
    long long v = 0;
    if (t.size() != 1 || !io::parse_int(t[0], v))
      throw file_error(path, lr.line(), "expected one vertex index per line, found " + io::quote(line));
    if (v < 0 || v >= num_vertices)
      throw file_error(path, lr.line(), "vertex index " + std::to_string(v) + " is out of range (the mesh has " +
                                            std::to_string(num_vertices) + " vertices, 0-based)");
    out.push_back(static_cast<int>(v));
  }
  return out;
}

}  // namespace dfm
