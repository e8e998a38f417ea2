#pragma once
// Exception hierarchy of relief. Precondition violations and I/O failures throw one of these;
// defects in the data (a missing node, a DEM void) go to a Diagnostics sink instead.
// Every exception carries its context: the file, the stage, the OSM or road id where known.

#include <stdexcept>
#include <string>

namespace relief {

/// Base of every relief exception. `what()` is a complete, user-facing sentence.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The input is unusable: malformed file, no roads, DEM that does not cover the roads, ...
class InvalidInput : public Error {
 public:
  using Error::Error;
};

/// A file could not be opened, read or written.
class IoError : public Error {
 public:
  using Error::Error;
};

/// A coordinate reference system is unknown or a transformation between two CRSs failed.
class ProjectionError : public Error {
 public:
  using Error::Error;
};

/// An option's value that this input makes unusable, e.g. a sample spacing that would need
/// more samples than the memory limit allows: the call must change, not the data (a kind of
/// InvalidInput; the CLI reports it as bad usage).
class OptionError : public InvalidInput {
 public:
  using InvalidInput::InvalidInput;
};

/// The DEMs do not cover the roads (a kind of InvalidInput, with the uncovered share).
class CoverageError : public InvalidInput {
 public:
  CoverageError(const std::string& message, double uncovered_percent)
      : InvalidInput(message), uncovered_percent_(uncovered_percent) {}
  [[nodiscard]] double uncovered_percent() const { return uncovered_percent_; }

 private:
  double uncovered_percent_;
};

}  // namespace relief
