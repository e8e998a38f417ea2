// replay.js: a co-simulation's vehicles for the view (relief cosim writes it beside view.html).
#include <nlohmann/json.hpp>

#include "core/base64.h"
#include "relief/viewer/view_writer.h"

namespace relief {

std::string view_replay_script(const std::vector<ReplayTrack>& tracks) {
  nlohmann::json vehicles = nlohmann::json::array();
  double end_s = 0.0;
  for (const ReplayTrack& track : tracks) {
    if (track.keys.empty()) continue;
    std::vector<float> keys;
    keys.reserve(track.keys.size() * 7);
    for (const ReplayKey& k : track.keys)
      keys.insert(keys.end(), {static_cast<float>(k.t_s), static_cast<float>(k.position.x()),
                               static_cast<float>(k.position.y()), static_cast<float>(k.position.z()),
                               static_cast<float>(k.heading_rad), static_cast<float>(k.pitch_rad),
                               static_cast<float>(k.roll_rad)});
    std::string encoded;
    detail::append_base64(encoded, {reinterpret_cast<const char*>(keys.data()), keys.size() * sizeof(float)});
    const double hide_s = std::max(track.hide_after_s, track.keys.back().t_s);
    end_s = std::max(end_s, hide_s);
    vehicles.push_back({{"id", track.name},
                        {"size", {track.length_m, track.width_m, track.height_m}},
                        {"hide_s", hide_s},
                        {"keys", std::move(encoded)}});
  }
  const nlohmann::json replay = {{"end_s", end_s}, {"vehicles", std::move(vehicles)}};
  return "window.RELIEF_REPLAY = " + replay.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) +
         ";\n";
}

}  // namespace relief
