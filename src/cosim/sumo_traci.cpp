// SumoSession's calls against libtraci: SUMO as its own process, over TraCI (sumo_backend.h).
#include <libsumo/libtraci.h>

#include <csignal>

namespace relief::detail {
namespace {

// SIGPIPE ignored while a TraCI session lives, as network clients do: libtraci 1.15 writes to
// its socket after every connection attempt failed (and a SUMO that dies mid-run closes it),
// and the signal would kill relief instead of the write failing with an error it reports.
class SessionGuard {
 public:
  SessionGuard() {
    struct sigaction ignore {};
    ignore.sa_handler = SIG_IGN;
    sigemptyset(&ignore.sa_mask);
    saved_ok_ = sigaction(SIGPIPE, &ignore, &saved_) == 0;
  }
  ~SessionGuard() {
    if (saved_ok_) sigaction(SIGPIPE, &saved_, nullptr);
  }
  SessionGuard(const SessionGuard&) = delete;
  SessionGuard& operator=(const SessionGuard&) = delete;

 private:
  struct sigaction saved_ {};
  bool saved_ok_ = false;
};

}  // namespace
}  // namespace relief::detail

#include "cosim/sumo_backend.inc"

namespace relief::detail {

std::unique_ptr<SumoBackend> start_over_traci(const std::vector<std::string>& args) {
  auto backend = std::make_unique<Backend>();
  libtraci::Simulation::start(args);
  backend->opened();
  return backend;
}

std::unique_ptr<SumoBackend> attach_over_traci(const std::string& host, int port, int attempts) {
  auto backend = std::make_unique<Backend>();
  libtraci::Simulation::init(port, attempts, host);
  backend->opened();
  return backend;
}

}  // namespace relief::detail
