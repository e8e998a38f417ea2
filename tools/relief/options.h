#pragma once
// Command-line options bound straight to the library's option structs: each option writes its
// field of BuildOptions, and the default `--help` shows is that field's value, the library's
// default. Values that need a conversion go through the library's parsers (option_text.h and
// the parse_* beside each enum); a bad value is a CLI::ValidationError naming the option.

#include <CLI/CLI.hpp>

#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "relief/core/errors.h"
#include "relief/pipeline/build.h"

namespace relief::cli {

/// Registers --osm, --dem, --crs, --dem-unit, --interp, --bbox, --include-paths, --spacing,
/// bound to the input fields of `options` (which must outlive `app`'s parse).
void add_input_options(CLI::App& app, BuildOptions& options);

/// Accepts a finite number > 0 (CLI::PositiveNumber lets "nan" and "inf" through, and states
/// its range as 0 to 1.8e308 written out in full).
[[nodiscard]] const CLI::Validator& finite_positive();
/// Accepts a finite number >= 0.
[[nodiscard]] const CLI::Validator& finite_non_negative();

/// Runs `apply` (a library parse of `option`'s value); an InvalidInput it throws (OptionError
/// included) becomes a CLI::ValidationError naming `option`, with the library's message.
void parse_for(const std::string& option, const std::function<void()>& apply);

/// An option whose text a library parser turns into `field` (an enum): `parse` returns
/// nullopt for a bad value, which is reported as "'TEXT' is not <expected>". The default shown
/// is to_string(field).
template <class T>
CLI::Option* add_enum_option(CLI::App& app, const std::string& name, T& field,
                             std::optional<T> (*parse)(std::string_view), const std::string& expected,
                             const std::string& description) {
  const std::string option = name.substr(0, name.find(','));
  return app
      .add_option_function<std::string>(
          name,
          [&field, parse, option, expected](const std::string& text) {
            const std::optional<T> value = parse(text);
            if (!value) throw CLI::ValidationError(option, "'" + text + "' is not " + expected);
            field = *value;
          },
          description)
      ->default_str(std::string(to_string(field)));
}

/// Runs `body`, mapping relief's exceptions to exit codes and printing their message:
/// InvalidInput/IoError/ProjectionError -> 3, CLI::ValidationError and OptionError (an option
/// value the input makes unusable) -> 2, anything else -> 1.
int run_reporting_errors(const std::function<int()>& body);

}  // namespace relief::cli
