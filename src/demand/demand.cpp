#include "relief/demand/demand.h"

#include <nlohmann/json.hpp>
#include <pugixml.hpp>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "relief/core/atomic_file.h"
#include "relief/core/diagnostic_codes.h"
#include "relief/core/errors.h"
#include "relief/core/number_format.h"
#include "relief/core/subprocess.h"
#include "relief/core/xml_writer.h"
#include "relief/demand/grade_routing.h"
#include "relief/demand/traffic_counts.h"
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

template <typename F>
void write_file(const std::filesystem::path& path, F&& write) {
  std::ofstream out(path, std::ios::binary);
  write(out);
  if (!out) throw IoError("cannot write '" + path.string() + "'");
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
    for (std::string e; in >> e;) passages[e] += 1.0;
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
  write_file(path, [&](std::ostream& out) { out << text; });
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
  write_file(path, [&](std::ostream& out) { out << text; });
}

// The counts' part: candidates routed on the cars' weights, sampled to the counts; the share of
// counted edges the sampled routes carry within GEH 5. Returns the routes file.
std::filesystem::path counted_routes(const std::filesystem::path& net, const std::vector<NetEdge>& edges,
                                     const std::filesystem::path& counts_csv,
                                     const std::filesystem::path& out_dir, const std::string& stem,
                                     const std::filesystem::path& types,
                                     const std::filesystem::path& car_weights,
                                     const TrafficDemandOptions& options, TrafficDemand& result,
                                     nlohmann::ordered_json& per_edge, Diagnostics& diagnostics) {
  const std::vector<CountRow> rows = read_counts_csv(counts_csv);
  const CountsOnEdges counts = counts_on_edges(rows, edges);
  result.count_rows = rows.size();
  result.counted_edges = counts.edges.size();
  result.unmatched = counts.unmatched;
  if (counts.edges.empty()) {
    throw InvalidInput("no count of '" + counts_csv.string() + "' fits an edge of '" + net.string() + "'" +
                       (counts.unmatched.empty() ? std::string() : ": " + counts.unmatched.front()));
  }
  for (const std::string& message : counts.unmatched)
    diagnostics.report(Severity::warning, codes::kDemandCountUnmatched, counts_csv.string() + " " + message);
  const std::filesystem::path counts_xml = out_dir / (stem + ".counts.xml");
  write_file(counts_xml,
             [&](std::ostream& out) { write_edge_counts(out, counts, options.begin_s, options.end_s); });
  // Many more candidate trips than counted edges, so that routeSampler finds routes through
  // every count.
  const int candidates = std::max(500, 20 * static_cast<int>(counts.edges.size()));
  routed_trips(net, out_dir, stem + ".candidates", candidates, options, "car", "passenger", types,
               car_weights);
  std::filesystem::path sampled = out_dir / (stem + ".counted.rou.xml");
  run_tool({sumo_python(), sumo_tool("routeSampler.py").string(), "--route-files",
            (out_dir / (stem + ".candidates.rou.xml")).string(), "--edgedata-files", counts_xml.string(),
            "--output-file", sampled.string(), "--begin", fixed(options.begin_s, 2), "--end",
            fixed(options.end_s, 2), "--seed", std::to_string(options.seed), "--prefix", "count_",
            "--attributes", "type=\"car\" departLane=\"best\" departSpeed=\"max\""},
           out_dir, "routeSampler.py on '" + counts_xml.string() + "'");
  std::map<std::string, double> passages = edge_passages(sampled);
  result.vehicles += static_cast<std::size_t>(passages[""]);
  std::size_t ok = 0;
  for (const EdgeCount& c : counts.edges) {
    const double m = passages[c.edge];
    const double geh =
        m + c.count > 0.0 ? std::sqrt(2.0 * (m - c.count) * (m - c.count) / (m + c.count)) : 0.0;
    if (geh < kGehOk) ++ok;
    result.worst_geh = std::max(result.worst_geh, geh);
    per_edge.push_back({{"edge", c.edge}, {"count", c.count}, {"routed", m}, {"geh", geh}});
  }
  result.geh_ok_share = static_cast<double>(ok) / static_cast<double>(counts.edges.size());
  return sampled;
}

// The OD part: the zones as TAZ of their edges, the matrix as tazRelations, od2trips, and
// duarouter on the cars' weights. Returns the routes file.
std::filesystem::path od_routes(const std::filesystem::path& net, const std::vector<NetEdge>& edges,
                                const TrafficDemandInputs& inputs, const std::filesystem::path& out_dir,
                                const std::string& stem, const std::filesystem::path& types,
                                const std::filesystem::path& car_weights, const TrafficDemandOptions& options,
                                TrafficDemand& result) {
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
  const std::filesystem::path taz = out_dir / (stem + ".taz.xml"), od = out_dir / (stem + ".od.xml");
  const std::filesystem::path trips = out_dir / (stem + ".od.trips.xml");
  std::filesystem::path routes = out_dir / (stem + ".od.rou.xml");
  write_file(taz, [&](std::ostream& out) { write_taz(out, zones); });
  write_file(od, [&](std::ostream& out) { write_taz_relations(out, rows, options.begin_s, options.end_s); });
  run_tool(
      {sumo_tool("od2trips").string(), "--taz-files", taz.string(), "--tazrelation-files", od.string(),
       "--output-file", trips.string(), "--vtype", "car", "--prefix", "od_", "--seed",
       std::to_string(options.seed), "--departlane", "best", "--departspeed", "max", "--no-step-log", "true"},
      out_dir, "od2trips on '" + od.string() + "'");
  const std::filesystem::path used_types = out_dir / (stem + ".od.used_types.xml");
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
  if (!car_weights.empty()) route.insert(route.end(), {"--weight-files", car_weights.string()});
  run_tool(route, out_dir, "duarouter on '" + trips.string() + "'");
  std::filesystem::remove(used_types);
  result.od_trips = static_cast<std::size_t>(edge_passages(routes)[""]);
  result.vehicles += result.od_trips;
  return routes;
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
  if (inputs.counts_csv.empty() && inputs.od_csv.empty() && options.trucks == 0)
    throw InvalidInput("demand: nothing to make (give counts, an OD matrix with zones, or trucks)");
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
    write_file(weights[vclass], [&](std::ostream& out) { write_grade_weights(out, edges, vclass); });
  }
  const std::filesystem::path car_weights =
      options.grade_routing ? weights["passenger"] : std::filesystem::path();

  std::vector<std::string> route_files = {types.filename().string()};
  nlohmann::ordered_json per_edge = nlohmann::ordered_json::array();
  if (!inputs.counts_csv.empty()) {
    result.routes = counted_routes(net, edges, inputs.counts_csv, out_dir, stem, types, car_weights, options,
                                   result, per_edge, diagnostics);
    route_files.push_back(result.routes.filename().string());
  }
  if (!inputs.od_csv.empty()) {
    const std::filesystem::path od =
        od_routes(net, edges, inputs, out_dir, stem, types, car_weights, options, result);
    route_files.push_back(od.filename().string());
    if (result.routes.empty()) result.routes = od;
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
  j["od"] = inputs.od_csv.string();
  j["zones"] = inputs.zones.string();
  j["begin_s"] = options.begin_s;
  j["end_s"] = options.end_s;
  j["grade_routing"] = options.grade_routing;
  j["count_rows"] = result.count_rows;
  j["counted_edges"] = result.counted_edges;
  j["unmatched_rows"] = result.unmatched;
  j["od_rows"] = result.od_rows;
  j["zones_count"] = result.zones;
  j["od_trips"] = result.od_trips;
  j["vehicles"] = result.vehicles;
  j["trucks"] = result.trucks;
  j["geh_ok_share"] = result.geh_ok_share;
  j["worst_geh"] = result.worst_geh;
  j["edges"] = per_edge;
  j["config"] = result.config.string();
  write_file_atomically(out_dir / kDemandReportFile, j.dump(2) + "\n");
  return result;
}

}  // namespace relief
