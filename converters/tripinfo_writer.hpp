#pragma once
// tripinfo output (SUMO's tripinfo_file.xsd): one <tripinfo/> per finished trip, in the order the trips
// are handed over (SUMO writes them as vehicles arrive), with SUMO's attribute order. Lanes are written
// as lane ids; rerouteNo is 0 (LPSim does not reroute).
// vaporized is "" for a trip that reached its destination, "teleport" for one that ended by being removed in
// a teleport (TripRecord::teleported) and "traci" for one a remove command took out (TripRecord::removed).
#include <string>
#include <vector>

#include "converters/output_file.hpp"
#include "demand/demand.hpp"
#include "engine/samples.hpp"
#include "net/network.hpp"

namespace lpsim {

class TripinfoWriter {
 public:
  /// Opens `path` (".gz" gives gzip) and writes the root tag. `devices` names the vehicle devices listed
  /// in each trip's devices attribute as "<device>_<vehicle id>", in SUMO's order (tripinfo first, then
  /// e.g. fcd when FCD output is on). net and demand must outlive the writer.
  /// `continue_at` >= 0: the file a saved run left, continued from that byte (OutputFile), without a header.
  TripinfoWriter(const std::string& path, const Network& net, const Demand& demand,
                 std::vector<std::string> devices = {"tripinfo"}, int64_t continue_at = -1);
  ~TripinfoWriter();
  TripinfoWriter(const TripinfoWriter&) = delete;
  TripinfoWriter& operator=(const TripinfoWriter&) = delete;

  void write(const TripRecord& trip);
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
  std::vector<std::string> devices_;
  OutputFile out_;
};

}  // namespace lpsim
