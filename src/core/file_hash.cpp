#include "relief/core/file_hash.h"

#include <openssl/evp.h>

#include <array>
#include <fstream>
#include <memory>

#include "relief/core/errors.h"

namespace relief {
namespace {

class Sha256 {
 public:
  Sha256() : ctx_(EVP_MD_CTX_new(), &EVP_MD_CTX_free) {
    if (!ctx_ || EVP_DigestInit_ex(ctx_.get(), EVP_sha256(), nullptr) != 1) {
      throw Error("cannot start a SHA-256 digest (OpenSSL)");
    }
  }
  void update(const char* data, std::size_t size) { EVP_DigestUpdate(ctx_.get(), data, size); }
  std::string hex() {
    std::array<unsigned char, EVP_MAX_MD_SIZE> digest{};
    unsigned int size = 0;
    EVP_DigestFinal_ex(ctx_.get(), digest.data(), &size);
    static constexpr char kDigits[] = "0123456789abcdef";
    std::string out;
    for (unsigned int i = 0; i < size; ++i) {
      out += kDigits[digest[i] >> 4];
      out += kDigits[digest[i] & 15];
    }
    return out;
  }

 private:
  std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx_;
};

// The file a GDAL virtual path reads from: its shortest prefix after "/vsiNAME" that is a
// regular file ("/vsizip//data/a.zip/b.hgt" -> "/data/a.zip").
std::filesystem::path container_file(const std::filesystem::path& path) {
  const std::string text = path.string();
  if (text.rfind("/vsi", 0) != 0) return path;
  const std::size_t start = text.find('/', 1);
  if (start == std::string::npos) return path;
  std::error_code ec;
  for (std::size_t next = text.find('/', start + 1);; next = text.find('/', next + 1)) {
    std::filesystem::path candidate =
        text.substr(start, next == std::string::npos ? std::string::npos : next - start);
    if (std::filesystem::is_regular_file(candidate, ec)) return candidate;
    if (next == std::string::npos) return path;
  }
}

}  // namespace

std::string absolute_input_path(const std::string& path) {
  std::error_code ec;
  const auto absolute = [](const std::filesystem::path& p) {
    return std::filesystem::absolute(p).lexically_normal().string();
  };
  if (path.rfind("/vsi", 0) == 0) {
    const std::size_t start = path.find('/', 1);  // the end of "/vsiNAME"
    if (start == std::string::npos || start + 1 >= path.size() || path[start + 1] == '/') return path;
    // A relative container: the shortest prefix of the rest that is a regular file.
    const std::string rest = path.substr(start + 1);
    for (std::size_t next = rest.find('/');; next = rest.find('/', next + 1)) {
      const std::string candidate = rest.substr(0, next);
      if (std::filesystem::is_regular_file(candidate, ec))
        return path.substr(0, start + 1) + absolute(candidate) +
               (next == std::string::npos ? std::string() : rest.substr(next));
      if (next == std::string::npos) return path;
    }
  }
  const std::filesystem::path p(path);
  if (p.is_relative() && std::filesystem::exists(p, ec)) return absolute(p);
  return path;
}

std::string sha256_hex(std::string_view bytes) {
  Sha256 digest;
  digest.update(bytes.data(), bytes.size());
  return digest.hex();
}

std::string sha256_of_file(const std::filesystem::path& path) {
  const std::filesystem::path file = container_file(path);
  std::ifstream in(file, std::ios::binary);
  if (!in) throw IoError("cannot read " + file.string() + " to hash it");
  Sha256 digest;
  std::array<char, 1 << 16> block{};
  while (in) {
    in.read(block.data(), block.size());
    digest.update(block.data(), static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) throw IoError("cannot read " + file.string() + " to hash it");
  return digest.hex();
}

}  // namespace relief
