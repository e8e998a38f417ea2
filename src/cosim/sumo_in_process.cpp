// SumoSession's calls against libsumo: SUMO in this process (sumo_backend.h).
#include <libsumo/libsumo.h>

namespace relief::detail {
namespace {
struct SessionGuard {};
}  // namespace
}  // namespace relief::detail

#include "cosim/sumo_backend.inc"

namespace relief::detail {

std::unique_ptr<SumoBackend> start_in_process(const std::vector<std::string>& args) {
  auto backend = std::make_unique<Backend>();
  libsumo::Simulation::start(args);
  backend->opened();
  return backend;
}

}  // namespace relief::detail
