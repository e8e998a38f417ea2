#pragma once
// Private to the cosim module: cosim.html, the co-simulation's figures for a person (the
// surface checks, the egos, and with LiDARs a plot of what they saw and hid over time and the
// crests that hid most).

#include <string>

#include "relief/cosim/cosim.h"

namespace relief::detail {

[[nodiscard]] std::string cosim_html(const CosimInputs& inputs, const CosimOptions& options,
                                     const CosimResult& r);

}  // namespace relief::detail
