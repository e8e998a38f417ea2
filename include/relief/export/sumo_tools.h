#pragma once
// SUMO's own tools driven from the library: netconvert turns relief's plain XML into a
// .net.xml; randomTrips.py and duarouter make a quick demand. Looked for in $SUMO_HOME/bin,
// $SUMO_HOME/tools and on PATH (Debian: /usr/bin, /usr/share/sumo/tools).

#include <filesystem>
#include <optional>
#include <string>

#include "relief/core/subprocess.h"
#include "relief/export/sumo_network.h"

namespace relief {

/// $SUMO_HOME, else /usr/share/sumo when it exists.
[[nodiscard]] std::optional<std::filesystem::path> sumo_home();

/// NAME of a net file NAME.net.xml or NAME.net.xml.gz (else the file's stem): the name its
/// build's other files share (NAME.xodr, NAME.glb, NAME.sumo_mapping.json).
[[nodiscard]] std::string sumo_net_name(const std::filesystem::path& net);

/// A SUMO program or Python tool (netconvert, duarouter, randomTrips.py, routeSampler.py):
/// $SUMO_HOME/bin, $SUMO_HOME/tools, then PATH. Throws IoError naming it when it is missing.
[[nodiscard]] std::filesystem::path sumo_tool(const std::string& name);
/// The environment SUMO's tools need (SUMO_HOME, for their schemas and type maps).
[[nodiscard]] Environment sumo_tool_environment();
/// The interpreter for SUMO's Python tools: Debian's /usr/bin/python3 (whose packages, numpy
/// among them, the tools import) when it exists, else python3 on PATH.
[[nodiscard]] std::string sumo_python();

struct NetconvertRun {
  std::string net_xml;  ///< the .net.xml text
  std::string log;      ///< what netconvert said
  std::size_t warnings = 0;
};

/// Writes the plain files of `net` as `name`.{nod,edg,con}.xml into `work_dir` (which must
/// exist) and runs netconvert on them with every option that moves heights turned off
/// (--geometry.max-grade.fix false; offsets kept, no re-normalisation). Throws IoError when
/// netconvert is missing or fails (its messages in the text).
[[nodiscard]] NetconvertRun run_netconvert(const SumoPlainNetwork& net, const std::filesystem::path& work_dir,
                                           const std::string& name);

struct DemandOptions {
  int trips = 0;         ///< random trips to make
  double begin_s = 0.0;  ///< departures between begin and end
  double end_s = 0.0;    ///< 0: one departure per second, end = trips
  unsigned seed = 42;
  double step_length_s = 0.05;  ///< the seed paper's 20 Hz
};

struct DemandRun {
  std::string routes_xml;  ///< duarouter's routes
  std::string sumocfg;     ///< configuration naming `name`.net.xml and `name`.rou.xml
  std::size_t routes = 0;  ///< vehicles with a route
  std::string log;
};

/// Random trips on `work_dir`/`name`.net.xml (randomTrips.py, seeded), routed by duarouter,
/// and a .sumocfg with the step length. Throws IoError when a tool is missing or fails.
[[nodiscard]] DemandRun make_demand(const std::filesystem::path& work_dir, const std::string& name,
                                    const DemandOptions& options);

}  // namespace relief
