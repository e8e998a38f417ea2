#include "relief/core/scratch_dir.h"

#include <unistd.h>

#include <string>
#include <system_error>

#include "relief/core/errors.h"

namespace relief {

ScratchDir::ScratchDir(const std::filesystem::path& parent)
    : path_(parent / (".relief-sumo-" + std::to_string(::getpid()))) {
  std::error_code ec;
  std::filesystem::create_directories(path_, ec);
  if (ec) throw IoError("cannot create '" + path_.string() + "': " + ec.message());
}

ScratchDir::~ScratchDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

}  // namespace relief
