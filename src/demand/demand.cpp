#include "relief/demand/demand.h"

#include <nlohmann/json.hpp>
#include <pugixml.hpp>

#include <cmath>
#include <map>
#include <sstream>
#include <tuple>

#include "relief/core/atomic_file.h"
#include "relief/core/diagnostic_codes.h"
#include "relief/core/errors.h"
#include "relief/core/number_format.h"
#include "relief/core/subprocess.h"
#include "relief/core/xml_writer.h"
#include "relief/demand/grade_routing.h"
#include "relief/demand/traffic_counts.h"
#include "relief/demand/turn_counts.h"
#include "relief/demand/zones.h"
#include "relief/export/sumo_tools.h"

namespace relief {
namespace {

constexpr double kGehOk = 5.0;  // the usual acceptance threshold of a counted flow

std::string fixed(double v, int digits) {
  std::string s;
  append_fixed(s, v, digits);
  return s;
}

std::string tail(const std::string& text, std::size_t max_chars = 1500) {
  return text.size() <= max_chars ? text : "..." + text.substr(text.size() - max_chars);
}

void run_tool(const std::vector<std::string>& argv, const std::filesystem::path& dir,
              const std::string& what) {
  const ProcessResult r = run_process(argv, sumo_tool_environment(), dir);
  if (r.exit_code != 0) throw IoError(what + " failed: " + tail(r.output));
}

// Random trips between the net's fringes over [begin, end), routed by duarouter on `weights`
// (none: on the limits), for vehicles of `type` (defined in `types`).
void routed_trips(const std::filesystem::path& net, const std::filesystem::path& dir, const std::string& stem,
                  int trips, const TrafficDemandOptions& o, const std::string& type,
                  const std::string& vclass, const std::filesystem::path& types,
                  const std::filesystem::path& weights) {
  const std::filesystem::path trip_file = dir / (stem + ".trips.xml"), route_file = dir / (stem + ".rou.xml");
  const std::filesystem::path used_types = dir / (stem + ".used_types.xml");
  run_tool({sumo_python(),
            sumo_tool("randomTrips.py").string(),
            "--net-file",
            net.string(),
            "--output-trip-file",
            trip_file.string(),
            "--begin",
            fixed(o.begin_s, 2),
            "--end",
            fixed(o.end_s, 2),
            "--period",
            fixed((o.end_s - o.begin_s) / trips, 4),
            "--seed",
            std::to_string(o.seed),
            "--fringe-factor",
            "5",
            "--min-distance",
            "100",
            "--vclass",
            vclass,
            "--prefix",
            stem + "_",
            "--trip-attributes",
            "type=\"" + type + "\" departLane=\"best\" departSpeed=\"max\""},
           dir, "randomTrips.py on '" + net.string() + "'");
  std::vector<std::string> route = {sumo_tool("duarouter").string(),
                                    "--net-file",
                                    net.string(),
                                    "--route-files",
                                    trip_file.string(),
                                    "--additional-files",
                                    types.string(),
                                    "--output-file",
                                    route_file.string(),
                                    "--ignore-errors",
                                    "true",
                                    "--no-step-log",
                                    "true",
                                    "--seed",
                                    std::to_string(o.seed),
                                    "--vtype-output",
                                    used_types.string()};
  if (!weights.empty()) route.insert(route.end(), {"--weight-files", weights.string()});
  run_tool(route, dir, "duarouter on '" + trip_file.string() + "'");
  std::filesystem::remove(used_types);  // the types stay in one file of their own
}

// How many vehicles of the routes file pass each edge.
std::map<std::string, double> edge_passages(const std::filesystem::path& routes) {
  pugi::xml_document doc;
  if (!doc.load_file(routes.c_str())) throw IoError("cannot read '" + routes.string() + "'");
  std::map<std::string, std::string> named;
  for (const pugi::xml_node& r : doc.child("routes").children("route"))
    named[r.attribute("id").as_string()] = r.attribute("edges").as_string();
  std::map<std::string, double> passages;
  std::size_t vehicles = 0;
  for (const pugi::xml_node& v : doc.child("routes").children("vehicle")) {
    ++vehicles;
    std::string edges = v.child("route").attribute("edges").as_string();
    if (edges.empty()) edges = named[v.attribute("route").as_string()];
    std::istringstream in(edges);
    std::string previous;
    for (std::string e; in >> e; previous = e) {
      passages[e] += 1.0;
      if (!previous.empty()) passages[previous + " " + e] += 1.0;  // a turn (ids have no spaces)
    }
  }
  passages[""] = static_cast<double>(vehicles);
  return passages;
}

void write_types(const std::filesystem::path& path) {
  std::string text;
  XmlWriter xml(text, {.indent = 4});
  xml.declaration();
  xml.comment(
      "generated by relief: PHEMlight's fuel and CO2 follow the grade; the trucks keep SUMO's default class");
  xml.start("routes");
  xml.start("vType");
  xml.attribute("id", "car");
  xml.attribute("vClass", "passenger");
  xml.attribute("emissionClass", "PHEMlight/PC_G_EU4");
  xml.end("vType");
  xml.start("vType");
  xml.attribute("id", "truck");
  xml.attribute("vClass", "truck");
  xml.end("vType");
  xml.end("routes");
  write_file_atomically(path, text);
}

void write_config(const std::filesystem::path& path, const std::filesystem::path& net,
                  const std::vector<std::string>& route_files, const std::string& stem,
                  const TrafficDemandOptions& o) {
  std::string text;
  XmlWriter xml(text, {.indent = 4, .escape_apostrophe = true});
  xml.declaration();
  xml.comment("generated by relief demand");
  xml.start("configuration");
  const auto value = [&](const char* element, const std::string& v) {
    xml.start(element);
    xml.attribute("value", v);
    xml.end(element);
  };
  xml.start("input");
  value("net-file", std::filesystem::absolute(net).string());
  std::string files;
  for (const std::string& f : route_files) files += (files.empty() ? "" : ",") + f;
  value("route-files", files);
  xml.end("input");
  // The route files are SUMO's own tools' output: not validated against SUMO's schemas, which
  // SUMO finds only through SUMO_HOME (without it, it rejects them as "invalid document").
  xml.start("processing");
  value("xml-validation.routes", "never");
  xml.end("processing");
  xml.start("time");
  value("begin", fixed(o.begin_s, 2));
  value("step-length", fixed(o.step_s, 3));
  xml.end("time");
  xml.start("output");
  value("tripinfo-output", stem + ".tripinfo.xml");
  xml.end("output");
  xml.start("emissions");
  value("device.emissions.probability", "1");
  if (const auto home = sumo_home())
    value("phemlight-path", (*home / "data" / "emissions" / "PHEMlight").string() + "/");
  xml.end("emissions");
  xml.end("configuration");
  write_file_atomically(path, text);
}

// The counted part: edge counts and turn counts onto the net, candidate routes on the cars'
// weights, routeSampler.py on both. Returns the sampled routes.
std::filesystem::path counted_routes(const std::filesystem::path& net, const std::vector<NetEdge>& edges,
                                     const TrafficDemandInputs& inputs, const std::filesystem::path& out_dir,
                                     const std::string& stem, const std::filesystem::path& types,
                                     const std::filesystem::path& car_weights,
                                     const TrafficDemandOptions& options, TrafficDemand& result,
                                     nlohmann::ordered_json& per_edge, nlohmann::ordered_json& per_turn,
                                     Diagnostics& diagnostics) {
  CountsOnEdges counts;
  TurnsOnEdges turns;
  std::vector<std::string> tool = {sumo_python(), sumo_tool("routeSampler.py").string()};
  const auto report_unmatched = [&](const std::filesystem::path& file,
                                    const std::vector<std::string>& messages) {
    for (const std::string& message : messages) {
      result.unmatched.push_back(message);
      diagnostics.report(Severity::warning, codes::kDemandCountUnmatched, file.string() + " " + message);
    }
  };
  if (!inputs.counts_csv.empty()) {
    const std::vector<CountRow> rows = read_counts_csv(inputs.counts_csv);
    counts = counts_on_edges(rows, edges);
    result.count_rows = rows.size();
    report_unmatched(inputs.counts_csv, counts.unmatched);
  }
  if (!inputs.turns_csv.empty()) {
    const std::vector<TurnRow> rows = read_turn_counts_csv(inputs.turns_csv);
    turns = turns_on_edges(rows, edges);
    result.turn_rows = rows.size();
    report_unmatched(inputs.turns_csv, turns.unmatched);
  }
  result.counted_edges = counts.edges.size();
  result.counted_turns = turns.turns.size();
  if (counts.edges.empty() && turns.turns.empty()) {
    const std::filesystem::path& given = inputs.counts_csv.empty() ? inputs.turns_csv : inputs.counts_csv;
    throw InvalidInput("no count of '" + given.string() + "' fits the edges of '" + net.string() + "'" +
                       (result.unmatched.empty() ? std::string() : ": " + result.unmatched.front()));
  }
  if (!counts.edges.empty()) {
    const std::filesystem::path counts_xml = out_dir / (stem + ".counts.xml");
    write_file_atomically(counts_xml, [&](std::ostream& out) {
      write_edge_counts(out, counts, options.begin_s, options.end_s);
    });
    tool.insert(tool.end(), {"--edgedata-files", counts_xml.string()});
  }
  if (!turns.turns.empty()) {
    const std::filesystem::path turns_xml = out_dir / (stem + ".turns.xml");
    write_file_atomically(
        turns_xml, [&](std::ostream& out) { write_turn_counts(out, turns, options.begin_s, options.end_s); });
    tool.insert(tool.end(), {"--turn-files", turns_xml.string()});
  }
  // Many more candidate trips than counts, so that routeSampler finds routes through every one.
  const int candidates = std::max(500, 20 * static_cast<int>(counts.edges.size() + turns.turns.size()));
  routed_trips(net, out_dir, stem + ".candidates", candidates, options, "car", "passenger", types,
               car_weights);
  std::filesystem::path sampled = out_dir / (stem + ".counted.rou.xml");
  tool.insert(tool.end(), {"--route-files", (out_dir / (stem + ".candidates.rou.xml")).string(),
                           "--output-file", sampled.string(), "--begin", fixed(options.begin_s, 2), "--end",
                           fixed(options.end_s, 2), "--seed", std::to_string(options.seed), "--prefix",
                           "count_", "--attributes", "type=\"car\" departLane=\"best\" departSpeed=\"max\""});
  run_tool(tool, out_dir, "routeSampler.py on the counts");
  std::map<std::string, double> passages = edge_passages(sampled);
  result.vehicles += static_cast<std::size_t>(passages[""]);
  std::size_t ok = 0;
  const auto geh = [&](double routed, double count) {
    const double g =
        routed + count > 0.0 ? std::sqrt(2.0 * (routed - count) * (routed - count) / (routed + count)) : 0.0;
    if (g < kGehOk) ++ok;
    result.worst_geh = std::max(result.worst_geh, g);
    return g;
  };
  for (const EdgeCount& c : counts.edges) {
    const double m = passages[c.edge];
    per_edge.push_back({{"edge", c.edge}, {"count", c.count}, {"routed", m}, {"geh", geh(m, c.count)}});
  }
  for (const TurnCount& t : turns.turns) {
    const double m = passages[t.from + " " + t.to];
    per_turn.push_back(
        {{"from", t.from}, {"to", t.to}, {"count", t.count}, {"routed", m}, {"geh", geh(m, t.count)}});
  }
  result.geh_ok_share =
      static_cast<double>(ok) / static_cast<double>(counts.edges.size() + turns.turns.size());
  return sampled;
}

// The OD part: the zones as TAZ of their edges, the matrix as tazRelations (one per vehicle
// class), od2trips, and duarouter on that class's weights. Returns the routes files.
std::vector<std::filesystem::path> od_routes(const std::filesystem::path& net,
                                             const std::vector<NetEdge>& edges,
                                             const TrafficDemandInputs& inputs,
                                             const std::filesystem::path& out_dir, const std::string& stem,
                                             const std::filesystem::path& types,
                                             const std::map<std::string, std::filesystem::path>& weights,
                                             const TrafficDemandOptions& options, TrafficDemand& result) {
  std::vector<Zone> zones = read_zones_geojson(inputs.zones, read_net_location(net));
  assign_edges(zones, edges);
  const std::vector<OdRow> rows = read_od_csv(inputs.od_csv);
  std::map<std::string, std::size_t> edges_of;
  for (const Zone& z : zones) edges_of[z.id] = z.edges.size();
  for (const OdRow& r : rows) {
    for (const std::string& zone : {r.origin, r.destination}) {
      const auto it = edges_of.find(zone);
      if (it == edges_of.end())
        throw InvalidInput("'" + inputs.od_csv.string() + "' line " + std::to_string(r.line) + ": zone '" +
                           zone + "' is not in '" + inputs.zones.string() + "'");
      if (it->second == 0)
        throw InvalidInput("'" + inputs.od_csv.string() + "' line " + std::to_string(r.line) + ": zone '" +
                           zone + "' holds no edge of '" + net.string() + "'");
    }
  }
  result.od_rows = rows.size();
  result.zones = zones.size();
  const std::filesystem::path taz = out_dir / (stem + ".taz.xml");
  write_file_atomically(taz, [&](std::ostream& out) { write_taz(out, zones); });
  std::vector<std::filesystem::path> routes_files;
  // (vehicle type, SUMO class of its weights, file suffix)
  for (const auto& [vtype, vclass, suffix] :
       {std::tuple<std::string, std::string, std::string>{"car", "passenger", ""},
        {"truck", "truck", "_truck"}}) {
    std::vector<OdRow> of_type;
    for (const OdRow& r : rows)
      if (r.vtype == vtype) of_type.push_back(r);
    if (of_type.empty() && vtype != "car") continue;
    const std::string name = stem + ".od" + suffix;
    const std::filesystem::path od = out_dir / (name + ".xml"), trips = out_dir / (name + ".trips.xml");
    const std::filesystem::path routes = out_dir / (name + ".rou.xml");
    write_file_atomically(
        od, [&](std::ostream& out) { write_taz_relations(out, of_type, options.begin_s, options.end_s); });
    run_tool({sumo_tool("od2trips").string(), "--taz-files", taz.string(), "--tazrelation-files", od.string(),
              "--output-file", trips.string(), "--vtype", vtype, "--prefix", "od" + suffix + "_", "--seed",
              std::to_string(options.seed), "--departlane", "best", "--departspeed", "max", "--no-step-log",
              "true"},
             out_dir, "od2trips on '" + od.string() + "'");
    const std::filesystem::path used_types = out_dir / (name + ".used_types.xml");
    std::vector<std::string> route = {sumo_tool("duarouter").string(),
                                      "--net-file",
                                      net.string(),
                                      "--route-files",
                                      trips.string(),
                                      "--additional-files",
                                      (types.string() + "," + taz.string()),
                                      "--output-file",
                                      routes.string(),
                                      "--ignore-errors",
                                      "true",
                                      "--no-step-log",
                                      "true",
                                      "--seed",
                                      std::to_string(options.seed),
                                      "--vtype-output",
                                      used_types.string(),
                                      "--with-taz",
                                      "true"};
    const auto w = weights.find(vclass);
    if (w != weights.end()) route.insert(route.end(), {"--weight-files", w->second.string()});
    run_tool(route, out_dir, "duarouter on '" + trips.string() + "'");
    std::filesystem::remove(used_types);
    const auto trips_routed = static_cast<std::size_t>(edge_passages(routes)[""]);
    result.od_trips += trips_routed;
    if (vtype == "truck") result.od_truck_trips = trips_routed;
    routes_files.push_back(routes);
  }
  result.vehicles += result.od_trips;
  return routes_files;
}

}  // namespace

TrafficDemand make_traffic_demand(const std::filesystem::path& net_path, const TrafficDemandInputs& inputs,
                                  const std::filesystem::path& out_path, const TrafficDemandOptions& options,
                                  Diagnostics& diagnostics) {
  // SUMO's tools run in the output directory: every path absolute.
  const std::filesystem::path net = std::filesystem::absolute(net_path);
  const std::filesystem::path out_dir = std::filesystem::absolute(out_path);
  if (!(std::isfinite(options.begin_s) && std::isfinite(options.end_s) && options.end_s > options.begin_s))
    throw InvalidInput("demand: the interval must be finite with its end after its begin");
  if (options.trucks < 0) throw InvalidInput("demand: the number of trucks must be >= 0");
  if (inputs.od_csv.empty() != inputs.zones.empty())
    throw InvalidInput("demand: an OD matrix needs its zones and zones their OD matrix");
  if (inputs.counts_csv.empty() && inputs.turns_csv.empty() && inputs.od_csv.empty() && options.trucks == 0)
    throw InvalidInput(
        "demand: nothing to make (give counts, turn counts, an OD matrix with zones, or trucks)");
  const std::vector<NetEdge> edges = read_net_edges(net);
  TrafficDemand result;

  std::filesystem::create_directories(out_dir);
  const std::string stem = sumo_net_name(net);
  const std::filesystem::path types = out_dir / (stem + ".vtypes.xml");
  write_types(types);
  std::map<std::string, std::filesystem::path> weights;
  for (const std::string vclass : {"passenger", "truck"}) {
    if (!options.grade_routing) break;
    weights[vclass] = out_dir / (stem + ".grade_" + vclass + ".weights.xml");
    write_file_atomically(weights[vclass],
                          [&](std::ostream& out) { write_grade_weights(out, edges, vclass); });
  }
  const std::filesystem::path car_weights =
      options.grade_routing ? weights["passenger"] : std::filesystem::path();

  std::vector<std::string> route_files = {types.filename().string()};
  nlohmann::ordered_json per_edge = nlohmann::ordered_json::array();
  nlohmann::ordered_json per_turn = nlohmann::ordered_json::array();
  if (!inputs.counts_csv.empty() || !inputs.turns_csv.empty()) {
    result.routes = counted_routes(net, edges, inputs, out_dir, stem, types, car_weights, options, result,
                                   per_edge, per_turn, diagnostics);
    route_files.push_back(result.routes.filename().string());
  }
  if (!inputs.od_csv.empty()) {
    for (const std::filesystem::path& od :
         od_routes(net, edges, inputs, out_dir, stem, types, weights, options, result)) {
      route_files.push_back(od.filename().string());
      if (result.routes.empty()) result.routes = od;
    }
  }
  if (options.trucks > 0) {
    routed_trips(net, out_dir, stem + ".trucks", options.trucks, options, "truck", "truck", types,
                 options.grade_routing ? weights["truck"] : std::filesystem::path());
    route_files.push_back(stem + ".trucks.rou.xml");
    result.trucks = static_cast<std::size_t>(edge_passages(out_dir / (stem + ".trucks.rou.xml"))[""]);
    result.vehicles += result.trucks;
  }
  result.config = out_dir / (stem + ".demand.sumocfg");
  write_config(result.config, net, route_files, stem, options);

  nlohmann::ordered_json j;
  j["net"] = net.string();
  j["counts"] = inputs.counts_csv.string();
  j["turn_counts"] = inputs.turns_csv.string();
  j["od"] = inputs.od_csv.string();
  j["zones"] = inputs.zones.string();
  j["begin_s"] = options.begin_s;
  j["end_s"] = options.end_s;
  j["grade_routing"] = options.grade_routing;
  j["count_rows"] = result.count_rows;
  j["counted_edges"] = result.counted_edges;
  j["turn_rows"] = result.turn_rows;
  j["counted_turns"] = result.counted_turns;
  j["unmatched_rows"] = result.unmatched;
  j["od_rows"] = result.od_rows;
  j["zones_count"] = result.zones;
  j["od_trips"] = result.od_trips;
  j["od_truck_trips"] = result.od_truck_trips;
  j["vehicles"] = result.vehicles;
  j["trucks"] = result.trucks;
  j["geh_ok_share"] = result.geh_ok_share;
  j["worst_geh"] = result.worst_geh;
  j["edges"] = per_edge;
  j["turns"] = per_turn;
  j["config"] = result.config.string();
  write_file_atomically(out_dir / kDemandReportFile, j.dump(2) + "\n");
  return result;
}

}  // namespace relief
