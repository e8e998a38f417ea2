#pragma once
// The viewer's web assets, embedded when relief is compiled (cmake/EmbedText.cmake writes
// view_assets.cpp in the build tree from src/viewer/web: the page template, its style, and
// the esbuild bundle of the viewer with three.js).

#include <string_view>

namespace relief::detail {

extern const std::string_view kViewPageTemplate;  ///< view.html with {{TITLE}}, {{STYLE}}, {{SCRIPT}}
extern const std::string_view kViewStyle;
extern const std::string_view kViewScript;

}  // namespace relief::detail
