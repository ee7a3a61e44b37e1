#pragma once
// Bounds-checked reading of little/big-endian scalars from a byte buffer, for the binary readers.
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

#include "core/util/error.h"

namespace dfm::io {

inline bool host_is_little_endian() {
  const uint16_t one = 1;
  unsigned char b;
  std::memcpy(&b, &one, 1);
  return b == 1;
}

class ByteCursor {
 public:
  ByteCursor(const std::string& path, std::string_view data, size_t pos) : path_(path), data_(data), pos_(pos) {}
  // Copies `n` bytes into `out` (swapping to host order when the file's order differs); throws with the
  // offset and `what` when fewer than n bytes remain.
  void read(void* out, size_t n, bool file_little_endian, const std::string& what) {
    if (n > data_.size() - pos_)
      throw byte_error(path_, static_cast<long long>(pos_),
                       "unexpected end of file while reading " + what + " (" + std::to_string(n) + " bytes needed, " +
                           std::to_string(data_.size() - pos_) + " left)");
    std::memcpy(out, data_.data() + pos_, n);
    if (file_little_endian != host_is_little_endian()) {
      unsigned char* b = static_cast<unsigned char*>(out);
      for (size_t i = 0; i < n / 2; ++i) std::swap(b[i], b[n - 1 - i]);
    }
    pos_ += n;
  }
  size_t pos() const { return pos_; }
  size_t left() const { return data_.size() - pos_; }
  [[noreturn]] void fail(size_t at, const std::string& problem) const {
    throw byte_error(path_, static_cast<long long>(at), problem);
  }

 private:
  std::string path_;
  std::string_view data_;
  size_t pos_;
};

}  // namespace dfm::io
