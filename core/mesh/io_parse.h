#pragma once
// Shared parsing helpers for the readers in io_*.cpp: whole-file loading, strict number parsing,
// a whitespace tokenizer and a line reader that both track line numbers, and count sanity checks
// that refuse absurd element counts before anything is allocated.
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/util/error.h"

namespace dfm::io {

// The whole file as bytes; errors name the path (missing, directory, unreadable).
std::string read_file(const std::string& path);

// Whole-token parses; false on any trailing garbage, empty token or overflow. Accepts a leading '+'.
bool parse_double(std::string_view s, double& out);
bool parse_int(std::string_view s, long long& out);

// Splits a line into whitespace-separated tokens (reuses `out`).
void split_ws(std::string_view line, std::vector<std::string_view>& out);

// Refuses a declared element count that cannot be right: negative, above INT_MAX, or needing more than
// `bytes_left` bytes at `min_bytes_each` bytes per element. Called before any allocation.
void check_count(const std::string& path, long line, long long count, long long min_bytes_each,
                 long long bytes_left, const std::string& what);

// Whitespace-separated tokens with line numbers; '#' starts a comment to end of line when enabled.
class Tokenizer {
 public:
  Tokenizer(const std::string& path, std::string_view data, bool hash_comments, long first_line = 1);
  // Next token, or false at end of data.
  bool next(std::string_view& tok);
  // Next token; at end of data throws "unexpected end of file, expected <what>".
  std::string_view expect(const std::string& what);
  double real(const std::string& what);          // finite double
  long long integer(const std::string& what);    // integer
  // As real(what()) and integer(what()), with the message built only for a bad token (a reader's hot
  // loop: no string per token).
  template <class What>
  double real_or(const What& what) {
    const size_t pos = pos_;
    const long line = line_;
    std::string_view t;
    double v;
    if (next(t) && parse_double(t, v) && std::isfinite(v)) return v;
    pos_ = pos, line_ = line;
    return real(what());
  }
  template <class What>
  long long integer_or(const What& what) {
    const size_t pos = pos_;
    const long line = line_;
    std::string_view t;
    long long v;
    if (next(t) && parse_int(t, v)) return v;
    pos_ = pos, line_ = line;
    return integer(what());
  }
  long line() const { return line_; }
  long long bytes_left() const { return static_cast<long long>(data_.size() - pos_); }
  size_t pos() const { return pos_; }
  [[noreturn]] void fail(const std::string& problem) const;
  const std::string& path() const { return path_; }

 private:
  void skip_space();
  std::string path_;
  std::string_view data_;
  size_t pos_ = 0;
  long line_ = 1;
  bool comments_;
};

// Lines with their 1-based numbers; strips a trailing '\r'.
class LineReader {
 public:
  explicit LineReader(std::string_view data) : data_(data) {}
  bool next(std::string_view& line);
  long line() const { return line_; }
  long long bytes_left() const { return static_cast<long long>(data_.size() - pos_); }

 private:
  std::string_view data_;
  size_t pos_ = 0;
  long line_ = 0;
};

// Removes a '#' comment and surrounding whitespace.
std::string_view strip_comment(std::string_view line);

// A token for an error message, quoted and shortened.
std::string quote(std::string_view token);

// "1.5" style number for messages.
std::string num(double x);

}  // namespace dfm::io
