#include "relief/core/atomic_file.h"

#include <fstream>
#include <random>
#include <system_error>

#include "relief/core/errors.h"

namespace relief {
namespace {

std::filesystem::path temporary_name(const std::filesystem::path& path) {
  static thread_local std::mt19937_64 rng{std::random_device{}()};
  auto tmp = path;
  tmp += ".tmp-" + std::to_string(rng() % 1000000000ULL);
  return tmp;
}

// Writes `write`'s output to a fresh temporary beside `path` and returns its name.
std::filesystem::path write_temporary(const std::filesystem::path& path,
                                      const std::function<void(std::ostream&)>& write) {
  auto tmp = temporary_name(path);
  try {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw IoError("cannot create '" + tmp.string() + "' for writing");
    write(out);
    out.flush();
    if (!out) throw IoError("cannot write '" + path.string() + "' (disk full?)");
  } catch (...) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw;
  }
  return tmp;
}

void rename_over(const std::filesystem::path& tmp, const std::filesystem::path& target) {
  std::error_code ec;
  std::filesystem::rename(tmp, target, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw IoError("cannot move the finished output onto '" + target.string() + "': " + ec.message());
  }
}

}  // namespace

void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write) {
  rename_over(write_temporary(path, write), path);
}

void write_file_atomically(const std::filesystem::path& path, std::string_view content) {
  write_file_atomically(path, [&](std::ostream& out) {
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
  });
}

OutputSet::~OutputSet() {
  for (const auto& p : pending_) {
    std::error_code ec;
    std::filesystem::remove(p.temporary, ec);
  }
}

void OutputSet::add(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write) {
  pending_.push_back({write_temporary(path, write), path});
}

void OutputSet::commit() {
  for (const auto& p : pending_) rename_over(p.temporary, p.target);
  pending_.clear();
}

}  // namespace relief
