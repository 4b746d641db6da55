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
  /// `continue_at` >= 0: the file a saved run left, continued from that byte (OutputFile), without a header.
  explicit SummaryWriter(const std::string& path, int64_t continue_at = -1);
  ~SummaryWriter();
  SummaryWriter(const SummaryWriter&) = delete;
  SummaryWriter& operator=(const SummaryWriter&) = delete;

  void write(const SummaryRow& row);
  /// Hands what was written so far to the file (OutputFile::flush). Called between records, so that a file
  /// cut short by a later kill holds them all and lacks only its closing tag.
  void flush() { out_.flush(); }
  /// Everything written so far handed to the file: where a resumed run continues it (OutputFile).
  uint64_t continue_point() { return out_.continue_point(); }

  /// Writes the closing tag and closes the file (InputError on failure); later calls do nothing.
  void close();

 private:
  OutputFile out_;
};

}  // namespace lpsim
