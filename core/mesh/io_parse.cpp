#include "core/mesh/io_parse.h"

#include <cctype>
#include <charconv>
#include <climits>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/util/atomic_file.h"

namespace dfm::io {

std::string read_file(const std::string& path) {
  require_readable_file(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw file_error(path, 0, "cannot open for reading");
  std::string data;
  in.seekg(0, std::ios::end);
  std::streamoff size = in.tellg();
  if (size < 0) throw file_error(path, 0, "cannot determine file size");
  in.seekg(0, std::ios::beg);
  data.resize(static_cast<size_t>(size));
  if (size > 0 && !in.read(data.data(), size)) throw file_error(path, 0, "read failed");
  return data;
}

bool parse_double(std::string_view s, double& out) {
  if (!s.empty() && s[0] == '+') s.remove_prefix(1);
  if (s.empty()) return false;
  auto r = std::from_chars(s.data(), s.data() + s.size(), out);
  if (r.ec == std::errc::result_out_of_range) {  // denormals/overflow: fall back to strtod's answer
    std::string tmp(s);
    char* end = nullptr;
    out = std::strtod(tmp.c_str(), &end);
    return end == tmp.c_str() + tmp.size();
  }
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

bool parse_int(std::string_view s, long long& out) {
  if (!s.empty() && s[0] == '+') s.remove_prefix(1);
  if (s.empty()) return false;
  auto r = std::from_chars(s.data(), s.data() + s.size(), out);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

void split_ws(std::string_view line, std::vector<std::string_view>& out) {
  out.clear();
  size_t i = 0, n = line.size();
  while (i < n) {
    while (i < n && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    size_t j = i;
    while (j < n && !std::isspace(static_cast<unsigned char>(line[j]))) ++j;
    if (j > i) out.push_back(line.substr(i, j - i));
    i = j;
  }
}

void check_count(const std::string& path, long line, long long count, long long min_bytes_each,
                 long long bytes_left, const std::string& what) {
  if (count < 0) throw file_error(path, line, "negative " + what + " count " + std::to_string(count));
  if (count > INT_MAX)
    throw file_error(path, line, what + " count " + std::to_string(count) + " is too large (limit " +
                                     std::to_string(INT_MAX) + ")");
  if (min_bytes_each > 0 && count > bytes_left / min_bytes_each)
    throw file_error(path, line, what + " count " + std::to_string(count) + " needs at least " +
                                     std::to_string(count * min_bytes_each) + " more bytes but only " +
                                     std::to_string(bytes_left) + " remain (truncated file or wrong count)");
}

Tokenizer::Tokenizer(const std::string& path, std::string_view data, bool hash_comments, long first_line)
    : path_(path), data_(data), line_(first_line), comments_(hash_comments) {}

void Tokenizer::skip_space() {
  while (pos_ < data_.size()) {
    char c = data_[pos_];
    if (c == '\n') {
      ++line_;
      ++pos_;
    } else if (std::isspace(static_cast<unsigned char>(c))) {
      ++pos_;
    } else if (comments_ && c == '#') {
      while (pos_ < data_.size() && data_[pos_] != '\n') ++pos_;
    } else {
      break;
    }
  }
}

bool Tokenizer::next(std::string_view& tok) {
  skip_space();
  if (pos_ >= data_.size()) return false;
  size_t start = pos_;
  while (pos_ < data_.size() && !std::isspace(static_cast<unsigned char>(data_[pos_])) &&
         !(comments_ && data_[pos_] == '#'))
    ++pos_;
  tok = data_.substr(start, pos_ - start);
  return true;
}

std::string_view Tokenizer::expect(const std::string& what) {
  std::string_view t;
  if (!next(t)) fail("unexpected end of file, expected " + what);
  return t;
}

std::string quote(std::string_view t) {
  std::string s;
  for (char c : t.substr(0, 40)) s += (std::isprint(static_cast<unsigned char>(c)) ? c : '?');
  if (t.size() > 40) s += "...";
  return "'" + s + "'";
}

double Tokenizer::real(const std::string& what) {
  std::string_view t = expect(what);
  double v;
  if (!parse_double(t, v)) fail("expected a number for " + what + ", found " + quote(t));
  if (!std::isfinite(v)) fail(what + " is not finite (" + quote(t) + ")");
  return v;
}

long long Tokenizer::integer(const std::string& what) {
  std::string_view t = expect(what);
  long long v;
  if (!parse_int(t, v)) fail("expected an integer for " + what + ", found " + quote(t));
  return v;
}

void Tokenizer::fail(const std::string& problem) const { throw file_error(path_, line_, problem); }

bool LineReader::next(std::string_view& line) {
  if (pos_ >= data_.size()) return false;
  size_t end = data_.find('\n', pos_);
  if (end == std::string_view::npos) end = data_.size();
  line = data_.substr(pos_, end - pos_);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  pos_ = end + 1;
  ++line_;
  return true;
}

std::string_view strip_comment(std::string_view line) {
  size_t h = line.find('#');
  if (h != std::string_view::npos) line = line.substr(0, h);
  size_t a = 0, b = line.size();
  while (a < b && std::isspace(static_cast<unsigned char>(line[a]))) ++a;
  while (b > a && std::isspace(static_cast<unsigned char>(line[b - 1]))) --b;
  return line.substr(a, b - a);
}

std::string num(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

}  // namespace dfm::io
