#include "relief/export/sumo_tools.h"

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "relief/core/errors.h"
#include "relief/core/number_format.h"
#include "relief/core/subprocess.h"
#include "relief/core/xml_writer.h"
#include "relief/export/sumo_plain_xml.h"

namespace relief {

std::string sumo_net_name(const std::filesystem::path& net) {
  std::string name = net.filename().string();
  for (const std::string suffix : {".net.xml.gz", ".net.xml"})
    if (name.size() > suffix.size() && name.ends_with(suffix))
      return name.substr(0, name.size() - suffix.size());
  return net.stem().string();
}

std::filesystem::path sumo_tool(const std::string& name) {
  std::vector<std::filesystem::path> dirs;
  if (const auto home = sumo_home()) dirs = {*home / "bin", *home / "tools"};
  const auto path = find_executable(name, dirs);
  if (!path) {
    throw IoError("SUMO's " + name +
                  " was not found (looked in $SUMO_HOME/bin, $SUMO_HOME/tools and on PATH); "
                  "install Debian's sumo and sumo-tools or set SUMO_HOME");
  }
  return *path;
}

Environment sumo_tool_environment() {
  if (const auto home = sumo_home()) return {{"SUMO_HOME", home->string()}};
  return {};
}

std::string sumo_python() {
  return std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
}

namespace {

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError("cannot read '" + path.string() + "'");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

template <typename F>
void write_text(const std::filesystem::path& path, F&& write) {
  std::ofstream out(path, std::ios::binary);
  write(out);
  if (!out) throw IoError("cannot write '" + path.string() + "'");
}

std::size_t count_lines_starting(const std::string& text, std::string_view prefix) {
  std::size_t n = 0;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(prefix, 0) == 0) ++n;
  }
  return n;
}

// Last lines of a tool's output, for an error message.
std::string tail(const std::string& text, std::size_t max_chars = 1500) {
  return text.size() <= max_chars ? text : "..." + text.substr(text.size() - max_chars);
}

}  // namespace

std::optional<std::filesystem::path> sumo_home() {
  if (const char* env = std::getenv("SUMO_HOME"); env && *env) return std::filesystem::path(env);
  std::error_code ec;
  if (std::filesystem::is_directory("/usr/share/sumo", ec)) return std::filesystem::path("/usr/share/sumo");
  return std::nullopt;
}

NetconvertRun run_netconvert(const SumoPlainNetwork& net, const std::filesystem::path& work_dir,
                             const std::string& name) {
  const std::filesystem::path nod = work_dir / (name + ".nod.xml"), edg = work_dir / (name + ".edg.xml"),
                              con = work_dir / (name + ".con.xml"), out = work_dir / (name + ".net.xml");
  write_text(nod, [&](std::ostream& o) { write_sumo_nodes(o, net); });
  write_text(edg, [&](std::ostream& o) { write_sumo_edges(o, net); });
  write_text(con, [&](std::ostream& o) { write_sumo_connections(o, net); });
  // netconvert runs in the work directory on the files' bare names: its file options are lists
  // split at commas, so a comma anywhere in the output directory's path ("--out box_9.5,47.1")
  // would cut the path apart.
  std::vector<std::string> argv = {sumo_tool("netconvert").string(), "--node-files", nod.filename().string(),
                                   "--edge-files", edg.filename().string(), "--connection-files",
                                   con.filename().string(), "--output-file", out.filename().string(),
                                   // Heights are relief's: no grade "fix", no offset normalisation.
                                   "--geometry.max-grade.fix", "false", "--offset.disable-normalization",
                                   "true",
                                   // Movements are relief's connections; no U-turns added.
                                   "--no-turnarounds", "true", "--precision", "3", "--output.street-names",
                                   "true", "--tls.default-type", "static"};
  // relief writes each lane's permissions itself; the edge types are names only.
  argv.insert(argv.end(), {"--ignore-errors.edge-type", "true"});
  // The files are relief's own, valid against SUMO's schemas (tests/pipeline/sumo_test.cpp checks
  // them with xmllint): validating them again took half of netconvert's time (1.1 of 2.4 s on NE).
  argv.insert(argv.end(), {"--xml-validation", "never"});
  const ProcessResult r = run_process(argv, sumo_tool_environment(), std::filesystem::absolute(work_dir));
  if (r.exit_code != 0) {
    throw IoError("netconvert failed on '" + nod.string() + "' (exit " + std::to_string(r.exit_code) +
                  "): " + tail(r.output));
  }
  NetconvertRun run;
  run.net_xml = read_text(out);
  run.log = r.output;
  run.warnings = count_lines_starting(r.output, "Warning");
  return run;
}

DemandRun make_demand(const std::filesystem::path& work_dir, const std::string& name,
                      const DemandOptions& options) {
  if (options.trips <= 0) throw InvalidInput("demand: the number of trips must be > 0");
  // randomTrips.py and duarouter run in the work directory, on the files' bare names: SUMO's
  // file options are lists split at commas, so a comma in the directory's path would cut it.
  const std::filesystem::path dir = std::filesystem::absolute(work_dir);
  const std::filesystem::path net = name + ".net.xml";
  const std::filesystem::path trips = name + ".trips.xml";
  const std::filesystem::path routes = name + ".rou.xml";
  const double end = options.end_s > options.begin_s ? options.end_s : options.begin_s + options.trips;
  const double period = (end - options.begin_s) / options.trips;
  std::string period_text, begin_text, end_text;
  append_fixed(period_text, period, 4);
  append_fixed(begin_text, options.begin_s, 2);
  append_fixed(end_text, end, 2);

  DemandRun run;
  const ProcessResult trips_run = run_process({sumo_python(),
                                               sumo_tool("randomTrips.py").string(),
                                               "--net-file",
                                               net.string(),
                                               "--output-trip-file",
                                               trips.string(),
                                               "--begin",
                                               begin_text,
                                               "--end",
                                               end_text,
                                               "--period",
                                               period_text,
                                               "--seed",
                                               std::to_string(options.seed),
                                               "--fringe-factor",
                                               "5",
                                               "--min-distance",
                                               "300",
                                               "--trip-attributes",
                                               "departLane=\"best\" departSpeed=\"max\"",
                                               "--validate"},
                                              sumo_tool_environment(), dir);
  run.log += trips_run.output;
  if (trips_run.exit_code != 0) {
    throw IoError("randomTrips.py failed on '" + (dir / net).string() + "': " + tail(trips_run.output));
  }
  const ProcessResult route_run =
      run_process({sumo_tool("duarouter").string(), "--net-file", net.string(), "--route-files",
                   trips.string(), "--output-file", routes.string(), "--ignore-errors", "true",
                   "--no-step-log", "true", "--seed", std::to_string(options.seed)},
                  sumo_tool_environment(), dir);
  run.log += route_run.output;
  if (route_run.exit_code != 0)
    throw IoError("duarouter failed on '" + (dir / trips).string() + "': " + tail(route_run.output));
  run.routes_xml = read_text(dir / routes);
  std::size_t pos = 0;
  while ((pos = run.routes_xml.find("<vehicle ", pos)) != std::string::npos) {
    ++run.routes;
    ++pos;
  }

  // NAME.sumocfg: the net and routes beside it, the start and step of the simulation.
  XmlWriter xml(run.sumocfg, {.indent = 4, .escape_apostrophe = true});
  xml.declaration();
  xml.comment("generated by relief");
  xml.start("configuration");
  xml.attribute("xmlns:xsi", "http://www.w3.org/2001/XMLSchema-instance");
  xml.attribute("xsi:noNamespaceSchemaLocation", "http://sumo.dlr.de/xsd/sumoConfiguration.xsd");
  const auto value = [&](const char* element, const std::string& text) {
    xml.start(element);
    xml.attribute("value", text);
    xml.end(element);
  };
  xml.start("input");
  value("net-file", name + ".net.xml");
  value("route-files", name + ".rou.xml");
  xml.end("input");
  xml.start("time");
  value("begin", begin_text);
  xml.start("step-length");
  xml.attribute_fixed("value", options.step_length_s, 3);
  xml.end("step-length");
  xml.end("time");
  xml.start("processing");
  value("time-to-teleport", "300");
  // duarouter's routes are not validated against SUMO's schemas, which SUMO finds only through
  // SUMO_HOME (without it, it rejects them as an "invalid document structure").
  value("xml-validation.routes", "never");
  xml.end("processing");
  xml.end("configuration");
  xml.finish();
  return run;
}

}  // namespace relief
