#pragma once
// FCD (floating car data) output in SUMO's fcd_file.xsd format: one <timestep> per sampled step, one
// <vehicle> per running vehicle with SUMO's attribute order (id x y angle type speed pos lane slope).
// x/y are the middle of the front bumper in net coordinates; angle is the back-to-front heading as SUMO
// computes it (see lane_geometry.hpp); slope is 0 (the network is planar).
// Steps without vehicles are still written, as an empty <timestep/>, as SUMO does.
#include <string>

#include "converters/lane_geometry.hpp"
#include "converters/output_file.hpp"
#include "demand/demand.hpp"
#include "engine/samples.hpp"
#include "net/network.hpp"

namespace lpsim {

class FcdWriter {
 public:
  /// Opens `path` (".gz" gives gzip) and writes the root tag. net and demand must outlive the writer.
  /// `continue_at` >= 0: the file a saved run left, continued from that byte (OutputFile), without a header.
  FcdWriter(const std::string& path, const Network& net, const Demand& demand, int64_t continue_at = -1);
  ~FcdWriter();
  FcdWriter(const FcdWriter&) = delete;
  FcdWriter& operator=(const FcdWriter&) = delete;

  void write(const FcdFrame& frame);
  /// Hands what was written so far to the file (OutputFile::flush). Called between records, so that a file
  /// cut short by a later kill holds them all and lacks only its closing tag.
  void flush() { out_.flush(); }
  /// Everything written so far handed to the file: where a resumed run continues it (OutputFile).
  uint64_t continue_point() { return out_.continue_point(); }

  /// Writes the closing tag and closes the file (InputError on failure); later calls do nothing.
  void close();

 private:
  const Network& net_;
  const Demand& demand_;
  LaneGeometry geometry_;
  OutputFile out_;
};

}  // namespace lpsim
