#pragma once
// summary output (SUMO's summary_file.xsd): one <step/> per simulation step with SUMO's attribute order.
// Means whose denominator is zero are written as -1, as SUMO does: meanWaitingTime (mean insertion delay)
// when nothing was inserted yet, meanTravelTime when no trip has ended, meanSpeed and meanSpeedRelative
// when no vehicle is running. duration is the step's wall time in whole milliseconds.
#include <string>

#include "converters/output_file.hpp"
#include "engine/samples.hpp"

namespace lpsim {

class SummaryWriter {
 public:
  /// Opens `path` (".gz" gives gzip) and writes the root tag.
  explicit SummaryWriter(const std::string& path);
  ~SummaryWriter();
  SummaryWriter(const SummaryWriter&) = delete;
  SummaryWriter& operator=(const SummaryWriter&) = delete;

  void write(const SummaryRow& row);
  /// Hands what was written so far to the file (OutputFile::flush). Called between records, so that a file
  /// cut short by a later kill holds them all and lacks only its closing tag.
  void flush() { out_.flush(); }
  /// Writes the closing tag and closes the file (InputError on failure); later calls do nothing.
  void close();

 private:
  OutputFile out_;
};

}  // namespace lpsim
