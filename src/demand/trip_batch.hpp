#pragma once
// Trips (and flows with from/to) collected into one routing batch. Identical requests are routed once and
// share one route slot. Endpoints are edges, or junctions: from a junction any normal edge leaving it
// with a car lane, to a junction any such edge entering it.
#include <cstdint>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "demand/flat_index.hpp"
#include "demand/route_table.hpp"
#include "net/router.hpp"

namespace lpsim {

/// Path endpoints and via edges of one trip or flow, as written.
struct TripEnds {
  const std::string& from;
  const std::string& to;
  const std::string& from_junction;
  const std::string& to_junction;
  const std::vector<std::string>& via;
};

class TripBatch {
 public:
  TripBatch(const Network& net, RouteTable& routes);

  /// Slot the trip `id` (a "trip" or "flow", says `kind`) of vClass mask `vclass` will use; filled by
  /// route_all() with a path that class may drive. Bad endpoints throw InputError at `loc` naming the id
  /// (or give a broken slot when route errors are ignored).
  /// random_stream non-zero: the trip is routed on its own with random edge-cost factors drawn from that
  /// stream (RouteRequest::random_stream), never shared with an identical trip.
  uint32_t add(const TripEnds& ends, uint32_t vclass, std::string_view kind, std::string_view id,
               const SourceLoc& loc, uint64_t random_stream = 0);

  /// Routes every pending request in one Router::route_all call (CchRouter::route_all with
  /// `contraction_hierarchy`: the same costs) and fills their slots. A request without a path: InputError
  /// "no route from X to Y for trip T" at the first trip's location, or a broken slot. Returns the wall time
  /// spent in the router (s), the hierarchy's construction included.
  double route_all(int threads, double minor_penalty = kMinorLinkPenalty, RandomWeights random = {},
                   bool contraction_hierarchy = false);
  size_t num_requests() const { return requests_.size(); }

 private:
  struct Pending {
    uint32_t slot;
    std::string description;  // "from X to Y for trip T"
    SourceLoc loc;
  };
  // Endpoint candidates: one edge, or the junction's leaving / entering edges. False: reason says why.
  bool endpoint(const std::string& edge, const std::string& junction, bool leaving,
                std::vector<uint32_t>& out, std::string& reason);
  void index_junctions();
  // Appends a request and its pending slot (a new slot: requests are deduplicated by the caller).
  uint32_t add_request(RouteRequest&& request, const TripEnds& ends, const std::string& who,
                       const SourceLoc& loc, bool packed);

  const Network& net_;
  RouteTable& routes_;
  std::vector<RouteRequest> requests_;
  std::vector<Pending> pending_;
  // Request key -> index in requests_: (origin, destination) packed for one-edge ends without via, which
  // is exact; a hash of the whole request otherwise, confirmed by comparing the requests.
  FlatIndex index_;
  std::vector<uint8_t> packed_;                              // per request: its key is the packed pair
  std::unordered_map<uint32_t, uint32_t> single_edge_slot_;  // from == to without via: that edge
  // Per junction, CSR lists of drivable normal edges leaving and entering it (built on first use).
  std::vector<uint32_t> leaving_begin_, leaving_, entering_begin_, entering_;
};

}  // namespace lpsim
