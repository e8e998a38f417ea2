#pragma once
// Private to the demand module: SUMO's data files (edge counts, edge and TAZ relations) share one
// frame, `<data><interval id begin end>` ... `</interval></data>`, and their counts' format.

#include <string>

#include "relief/core/xml_writer.h"

namespace relief::detail {

/// Writes the declaration, `comment`, and opens `<data><interval id begin end>` (seconds, 2
/// decimals).
void open_data_interval(XmlWriter& xml, const std::string& comment, const std::string& id, double begin_s,
                        double end_s);

/// Closes the interval and the data.
void close_data_interval(XmlWriter& xml);

/// A count as the data files give it: 2 decimals.
[[nodiscard]] std::string count_text(double count);

}  // namespace relief::detail
