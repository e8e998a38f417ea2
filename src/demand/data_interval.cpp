#include "demand/data_interval.h"

#include "relief/core/number_format.h"

namespace relief::detail {

void open_data_interval(XmlWriter& xml, const std::string& comment, const std::string& id, double begin_s,
                        double end_s) {
  xml.declaration();
  xml.comment(comment);
  xml.start("data");
  xml.start("interval");
  xml.attribute("id", id);
  xml.attribute("begin", count_text(begin_s));
  xml.attribute("end", count_text(end_s));
}

void close_data_interval(XmlWriter& xml) {
  xml.end("interval");
  xml.end("data");
}

std::string count_text(double count) {
  std::string text;
  append_fixed(text, count, 2);
  return text;
}

}  // namespace relief::detail
