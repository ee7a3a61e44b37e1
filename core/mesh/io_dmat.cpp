// .dmat dense matrices (libigl's format, see ../shared/data/README.md). Text: "cols rows" then the
// entries column by column. Binary: a first line "0 0", a second line "cols rows", then rows*cols
// little-endian doubles column by column. Non-finite entries are rejected.
#include <algorithm>
#include <climits>
#include <cmath>
#include <cstring>
#include <iomanip>

#include "core/mesh/io.h"
#include "core/mesh/io_parse.h"
#include "core/util/atomic_file.h"

namespace dfm {
namespace {

static_assert(sizeof(double) == 8, "dmat needs 8-byte doubles");

bool little_endian() {
  const uint16_t one = 1;
  unsigned char b;
  std::memcpy(&b, &one, 1);
  return b == 1;
}

void check_dims(const std::string& path, long line, long long cols, long long rows) {
  if (cols < 0 || rows < 0)
    throw file_error(path, line, "negative size " + std::to_string(cols) + " x " + std::to_string(rows));
  if (cols > INT_MAX || rows > INT_MAX)
    throw file_error(path, line, "size " + std::to_string(rows) + " rows x " + std::to_string(cols) +
                                     " columns is too large");
}

Eigen::MatrixXd read_binary(const std::string& path, const std::string& data, size_t first_end) {
  size_t second_end = data.find('\n', first_end + 1);
  if (second_end == std::string::npos)
    throw byte_error(path, first_end + 1, "binary dmat: missing the second header line \"cols rows\"");
  std::string_view header(data.data() + first_end + 1, second_end - first_end - 1);
  std::vector<std::string_view> t;
  io::split_ws(header, t);
  long long cols, rows;
  if (t.size() != 2 || !io::parse_int(t[0], cols) || !io::parse_int(t[1], rows))
    throw file_error(path, 2, "binary dmat: second header line must be \"cols rows\", found " + io::quote(header));
  check_dims(path, 2, cols, rows);
  const long long start = static_cast<long long>(second_end + 1);
  const long long have = static_cast<long long>(data.size()) - start;
  const long long entries = rows * cols;  // both <= INT_MAX: fits in 63 bits; entries * 8 may not
  if (entries > have / 8 || have != entries * 8) {
    const bool short_file = entries > have / 8;
    throw byte_error(path, start, "binary dmat " + std::to_string(rows) + " x " + std::to_string(cols) + " needs " +
                                      (entries <= LLONG_MAX / 8 ? std::to_string(entries * 8) : std::string("too many")) +
                                      " bytes of doubles, file has " + std::to_string(have) +
                                      (short_file ? " (truncated)" : " (trailing bytes)"));
  }
  const long long need = entries * 8;
  Eigen::MatrixXd M(rows, cols);  // column-major, like the file
  if (need > 0) std::memcpy(M.data(), data.data() + start, static_cast<size_t>(need));  // data() is null when empty
  if (!little_endian())
    for (long long i = 0; i < rows * cols; ++i) {
      unsigned char* b = reinterpret_cast<unsigned char*>(M.data() + i);
      std::reverse(b, b + 8);
    }
  for (long long i = 0; i < rows * cols; ++i)
    if (!std::isfinite(M.data()[i]))
      throw byte_error(path, start + 8 * i, "entry (row " + std::to_string(i % rows + 1) + ", column " +
                                                std::to_string(i / rows + 1) + ") is not finite");
  return M;
}

}  // namespace

Eigen::MatrixXd read_dmat(const std::string& path) {
  std::string data = io::read_file(path);
  size_t first_end = data.find('\n');
  std::string_view first(data.data(), first_end == std::string::npos ? data.size() : first_end);
  std::vector<std::string_view> t;
  io::split_ws(first, t);
  if (t.size() == 2 && t[0] == "0" && t[1] == "0") {
    bool rest_blank = true;  // a lone "0 0" is the text form of an empty matrix
    for (size_t i = first.size(); i < data.size(); ++i) rest_blank = rest_blank && std::isspace((unsigned char)data[i]);
    if (rest_blank) return Eigen::MatrixXd();
    return read_binary(path, data, first_end);
  }
  io::Tokenizer tk(path, data, false);
  if (data.empty()) tk.fail("empty file (expected \"cols rows\")");
  long long cols = tk.integer("column count"), rows = tk.integer("row count");
  check_dims(path, tk.line(), cols, rows);
  if (tk.line() != 1) tk.fail("the first line must hold \"cols rows\"");
  io::check_count(path, 1, rows * cols, 2, tk.bytes_left(), "matrix entry");
  Eigen::MatrixXd M(rows, cols);
  for (long long c = 0; c < cols && rows > 0; ++c)  // rows == 0: do not spin through 2^31 empty columns
    for (long long r = 0; r < rows; ++r)
      M(r, c) = tk.real("entry (row " + std::to_string(r + 1) + ", column " + std::to_string(c + 1) + ")");
  std::string_view extra;
  if (tk.next(extra)) tk.fail("more entries than " + std::to_string(rows) + " x " + std::to_string(cols));
  return M;
}

void write_dmat(const std::string& path, const Eigen::MatrixXd& M, bool binary) {
  if (M.size() == 0 && M.rows() == 0 && M.cols() == 0) binary = true;  // text "0 0" would read as binary
  write_file_atomic(
      path,
      [&](std::ostream& o) {
        if (binary) {
          o << "0 0\n" << M.cols() << ' ' << M.rows() << '\n';
          Eigen::MatrixXd C = M;  // contiguous column-major
          if (!little_endian())
            for (Eigen::Index i = 0; i < C.size(); ++i) {
              unsigned char* b = reinterpret_cast<unsigned char*>(C.data() + i);
              std::reverse(b, b + 8);
            }
          o.write(reinterpret_cast<const char*>(C.data()), static_cast<std::streamsize>(C.size() * 8));
        } else {
          o << std::setprecision(17) << M.cols() << ' ' << M.rows() << '\n';
          for (Eigen::Index c = 0; c < M.cols() && M.rows() > 0; ++c)
            for (Eigen::Index r = 0; r < M.rows(); ++r) o << M(r, c) << '\n';
        }
      },
      binary);
}

}  // namespace dfm
