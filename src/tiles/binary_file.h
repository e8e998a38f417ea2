#pragma once
// Private to the tiles module: the little binary files a tile writes for the tiles built or
// merged after it (holds, owned surfaces): values appended in the machine's byte order (the
// files stay on the machines of one run), read back with bounds checks.

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <string_view>
#include <utility>

#include "relief/core/errors.h"

namespace relief::detail {

template <typename T>
void put(std::string& out, const T& value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

/// Reads a file put() wrote; `what` names its kind in the errors ("tile holds").
class BinaryReader {
 public:
  BinaryReader(const std::filesystem::path& path, std::string what) : path_(path), what_(std::move(what)) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError("cannot read " + path.string());
    data_.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  template <typename T>
  T get() {
    if (pos_ + sizeof(T) > data_.size()) throw InvalidInput(path_.string() + ": truncated " + what_);
    T value;
    std::memcpy(&value, data_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return value;
  }
  /// The file starts with `magic`; throws InvalidInput otherwise.
  void expect(std::string_view magic) {
    if (data_.compare(0, magic.size(), magic) != 0)
      throw InvalidInput(path_.string() + ": not a " + what_ + " file");
    pos_ = magic.size();
  }
  /// Throws InvalidInput unless every byte was read.
  void finish() const {
    if (pos_ != data_.size()) throw InvalidInput(path_.string() + ": trailing bytes in " + what_);
  }

 private:
  std::filesystem::path path_;
  std::string what_;
  std::string data_;
  std::size_t pos_ = 0;
};

}  // namespace relief::detail
