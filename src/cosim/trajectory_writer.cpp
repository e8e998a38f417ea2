#include "cosim/trajectory_writer.h"

#include <cstdio>
#include <system_error>

#include "relief/core/errors.h"
#include "relief/core/xml_writer.h"

namespace relief::detail {
namespace {

std::filesystem::path temporary_for(const std::filesystem::path& target) {
  std::string name = target.filename().string();
  name.insert(0, 1, '.');
  name += ".part";
  return target.parent_path() / name;
}

void open(std::ofstream& out, const std::filesystem::path& path) {
  out.open(path, std::ios::binary | std::ios::trunc);
  if (!out) throw IoError("cannot write '" + path.string() + "'");
}

// A CSV field (RFC 4180): quoted, with quotes doubled, when it holds a comma, a quote or a newline.
void put_csv_field(std::ostream& out, const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) {
    out << text;
    return;
  }
  out << '"';
  for (const char c : text) out << (c == '"' ? "\"\"" : std::string(1, c));
  out << '"';
}

}  // namespace

TrajectoryWriter::TrajectoryWriter(std::filesystem::path fcd, std::filesystem::path csv)
    : fcd_(std::move(fcd)),
      csv_(std::move(csv)),
      fcd_tmp_(temporary_for(fcd_)),
      csv_tmp_(temporary_for(csv_)) {
  open(fcd_out_, fcd_tmp_);
  open(csv_out_, csv_tmp_);
  fcd_out_
      << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<!-- relief cosim: SUMO's FCD format; x, y, z is the vehicle's centre on relief's road surface,\n"
      << "     pitch (nose up) and roll (right side down) in degrees from its four wheel contacts -->\n"
      << "<fcd-export>\n";
  csv_out_ << "time_s,id,type,lane,x_m,y_m,z_m,angle_deg,speed_mps,pitch_deg,roll_deg\n";
}

TrajectoryWriter::~TrajectoryWriter() {
  if (committed_) return;
  fcd_out_.close();
  csv_out_.close();
  std::error_code ignored;
  std::filesystem::remove(fcd_tmp_, ignored);
  std::filesystem::remove(csv_tmp_, ignored);
}

void TrajectoryWriter::begin_step(double time_s) {
  time_s_ = time_s;
  char line[64];
  std::snprintf(line, sizeof line, "  <timestep time=\"%.2f\">\n", time_s);
  fcd_out_ << line;
}

void TrajectoryWriter::add(const TrajectoryRow& row) {
  char numbers[256];
  std::snprintf(numbers, sizeof numbers,
                "x=\"%.3f\" y=\"%.3f\" z=\"%.3f\" angle=\"%.2f\" speed=\"%.2f\" pitch=\"%.3f\" roll=\"%.3f\"",
                row.x, row.y, row.z, row.angle_deg, row.speed_mps, row.pitch_deg, row.roll_deg);
  std::string& line = line_;
  line.assign("    <vehicle id=\"");
  append_xml_escaped(line, *row.id);
  line.append("\" ").append(numbers).append(" type=\"");
  append_xml_escaped(line, *row.type);
  line.append("\" lane=\"");
  append_xml_escaped(line, *row.lane);
  line.append("\"/>\n");
  fcd_out_ << line;
  std::snprintf(numbers, sizeof numbers, "%.3f,%.3f,%.3f,%.2f,%.2f,%.3f,%.3f", row.x, row.y, row.z,
                row.angle_deg, row.speed_mps, row.pitch_deg, row.roll_deg);
  char time[32];
  std::snprintf(time, sizeof time, "%.2f", time_s_);
  csv_out_ << time << ',';
  put_csv_field(csv_out_, *row.id);
  csv_out_ << ',';
  put_csv_field(csv_out_, *row.type);
  csv_out_ << ',';
  put_csv_field(csv_out_, *row.lane);
  csv_out_ << ',' << numbers << '\n';
}

void TrajectoryWriter::end_step() {
  fcd_out_ << "  </timestep>\n";
}

void TrajectoryWriter::commit() {
  fcd_out_ << "</fcd-export>\n";
  fcd_out_.close();
  csv_out_.close();
  if (!fcd_out_ || !csv_out_)
    throw IoError("cannot write the trajectories in '" + fcd_.parent_path().string() + "'");
  std::filesystem::rename(fcd_tmp_, fcd_);
  std::filesystem::rename(csv_tmp_, csv_);
  committed_ = true;
}

}  // namespace relief::detail
