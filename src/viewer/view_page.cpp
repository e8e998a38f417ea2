// view.html: the page template with its style and script (embedded at compile time) filled in.
#include <string>

#include "relief/core/errors.h"
#include "relief/core/xml_writer.h"
#include "relief/viewer/view_writer.h"
#include "viewer/view_assets.h"

namespace relief {
namespace {

void replace_all(std::string& text, std::string_view key, std::string_view value) {
  for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + value.size()))
    text.replace(at, key.size(), value);
}

}  // namespace

std::string view_page(const std::string& title, const ViewPageOptions& options) {
  std::vector<std::string> paths = options.scripts;
  paths.push_back(options.data_dir);
  paths.push_back(options.report);
  for (const std::string& path : paths)
    if (path.find_first_of("\"'<>\\") != std::string::npos)
      throw InvalidInput("view page: the path '" + path + "' has a quote, '<', '>' or a backslash");
  std::string extra;
  for (const std::string& script : options.scripts) extra += "<script src=\"" + script + "\"></script>\n";
  std::string page(detail::kViewPageTemplate);
  // The short fields first: the style and the script may hold any text, {{TITLE}} included.
  std::string escaped_title;
  append_xml_escaped(escaped_title, title);
  replace_all(page, "{{TITLE}}", escaped_title);
  replace_all(page, "{{DATA}}", options.data_dir);
  replace_all(page, "{{REPORT}}", options.report);
  replace_all(page, "{{EXTRA}}", extra);
  const std::size_t style = page.find("{{STYLE}}");
  page.replace(style, 9, detail::kViewStyle);
  const std::size_t script = page.find("{{SCRIPT}}", style + detail::kViewStyle.size());
  page.replace(script, 10, detail::kViewScript);
  return page;
}

}  // namespace relief
