#include "demand/trip_batch.hpp"

#include <chrono>

#include "kernels/rng.hpp"
#include "net/cch_router.hpp"

namespace lpsim {
namespace {

uint64_t hash_request(const RouteRequest& r) {
  uint64_t h = 0x5DEECE66Dull;
  auto mix = [&h](const std::vector<uint32_t>& part) {
    h = rng_mix64(h ^ part.size());
    for (uint32_t e : part) h = rng_mix64(h ^ e);
  };
  mix(r.origins);
  mix(r.destinations);
  mix(r.via);
  return rng_mix64(h ^ r.vclass);
}

bool same_request(const RouteRequest& a, const RouteRequest& b) {
  return a.origins == b.origins && a.destinations == b.destinations && a.via == b.via && a.vclass == b.vclass;
}

std::string endpoint_name(const std::string& edge, const std::string& junction) {
  return edge.empty() ? "junction '" + junction + "'" : "edge '" + edge + "'";
}

}  // namespace

TripBatch::TripBatch(const Network& net, RouteTable& routes) : net_(net), routes_(routes) {}

void TripBatch::index_junctions() {
  const uint32_t nj = net_.num_junctions();
  leaving_begin_.assign(nj + 1, 0);
  entering_begin_.assign(nj + 1, 0);
  auto drivable = [this](uint32_t e) { return !net_.edge_is_internal[e] && net_.edge_num_lanes[e] > 0; };
  for (uint32_t e = 0; e < net_.num_edges(); ++e) {
    if (!drivable(e)) continue;
    if (net_.edge_from_junction[e] >= 0) ++leaving_begin_[net_.edge_from_junction[e] + 1];
    if (net_.edge_to_junction[e] >= 0) ++entering_begin_[net_.edge_to_junction[e] + 1];
  }
  for (uint32_t j = 0; j < nj; ++j) {
    leaving_begin_[j + 1] += leaving_begin_[j];
    entering_begin_[j + 1] += entering_begin_[j];
  }
  leaving_.resize(leaving_begin_[nj]);
  entering_.resize(entering_begin_[nj]);
  std::vector<uint32_t> leave_fill(leaving_begin_.begin(), leaving_begin_.end() - 1);
  std::vector<uint32_t> enter_fill(entering_begin_.begin(), entering_begin_.end() - 1);
  for (uint32_t e = 0; e < net_.num_edges(); ++e) {  // ascending edge index within each junction
    if (!drivable(e)) continue;
    if (net_.edge_from_junction[e] >= 0) leaving_[leave_fill[net_.edge_from_junction[e]]++] = e;
    if (net_.edge_to_junction[e] >= 0) entering_[enter_fill[net_.edge_to_junction[e]]++] = e;
  }
}

bool TripBatch::endpoint(const std::string& edge, const std::string& junction, bool leaving,
                         std::vector<uint32_t>& out, std::string& reason) {
  if (!edge.empty()) {
    auto e = routes_.edges().drivable(edge, reason);
    if (e) out.push_back(*e);
    return e.has_value();
  }
  auto it = net_.junction_index.find(junction);
  if (it == net_.junction_index.end()) {
    reason = "unknown junction '" + junction + "'";
    return false;
  }
  if (leaving_begin_.empty()) index_junctions();
  const uint32_t j = it->second;
  const auto& begin = leaving ? leaving_begin_ : entering_begin_;
  const auto& edges = leaving ? leaving_ : entering_;
  out.assign(edges.begin() + begin[j], edges.begin() + begin[j + 1]);
  if (out.empty()) {
    reason = "junction '" + junction + "' has no edge " + (leaving ? "leaving" : "entering") +
             " it that a vehicle may use";
    return false;
  }
  return true;
}

uint32_t TripBatch::add(const TripEnds& ends, uint32_t vclass, std::string_view kind, std::string_view id,
                        const SourceLoc& loc, uint64_t random_stream) {
  const std::string who = std::string(kind) + " '" + std::string(id) + "'";
  if ((ends.from.empty() && ends.from_junction.empty()) || (ends.to.empty() && ends.to_junction.empty()))
    return routes_.add_broken(loc, who + " has neither a route nor both trip endpoints");
  RouteRequest request;
  request.vclass = vclass;
  request.random_stream = random_stream;
  std::string reason;
  if (!endpoint(ends.from, ends.from_junction, true, request.origins, reason) ||
      !endpoint(ends.to, ends.to_junction, false, request.destinations, reason))
    return routes_.add_broken(loc, reason + " in " + who, EdgeLookup::outside_car_map(reason));
  for (const auto& v : ends.via) {
    auto e = routes_.edges().drivable(v, reason);
    if (!e) return routes_.add_broken(loc, reason + " (via) in " + who, EdgeLookup::outside_car_map(reason));
    request.via.push_back(*e);
  }

  // SUMO drives a trip whose two ends are the same edge on that edge alone.
  if (request.via.empty() && !ends.from.empty() && ends.from == ends.to && random_stream == 0) {
    const uint32_t e = request.origins.front();
    auto it = single_edge_slot_.find(e);
    if (it == single_edge_slot_.end()) it = single_edge_slot_.emplace(e, routes_.add_resolved({e})).first;
    return it->second;
  }

  if (random_stream != 0) return add_request(std::move(request), ends, who, loc, false);
  const bool packed = request.origins.size() == 1 && request.destinations.size() == 1 && request.via.empty();
  // Packed keys of one vClass are exact; another class's may collide and is told apart by the comparison.
  const uint64_t key =
      packed ? (uint64_t{request.origins[0]} << 32 | request.destinations[0]) ^ rng_mix64(request.vclass)
             : hash_request(request);
  const auto next = static_cast<uint32_t>(requests_.size());
  const uint32_t known = index_.find_or_insert(key, next, [&](uint32_t r) {
    if (requests_[r].vclass != request.vclass) return false;
    return packed_[r] ? packed : !packed && same_request(requests_[r], request);
  });
  if (known != next) return pending_[known].slot;
  return add_request(std::move(request), ends, who, loc, packed);
}

uint32_t TripBatch::add_request(RouteRequest&& request, const TripEnds& ends, const std::string& who,
                                const SourceLoc& loc, bool packed) {
  const uint32_t slot = routes_.add_pending();  // filled by route_all()
  requests_.push_back(std::move(request));
  packed_.push_back(packed);
  pending_.push_back({slot,
                      "from " + endpoint_name(ends.from, ends.from_junction) + " to " +
                          endpoint_name(ends.to, ends.to_junction) + " for " + who,
                      loc});
  return slot;
}

double TripBatch::route_all(int threads, double minor_penalty, RandomWeights random,
                            bool contraction_hierarchy) {
  if (requests_.empty()) return 0;
  const auto t0 = std::chrono::steady_clock::now();
  Router router(net_, minor_penalty, random);
  const auto paths = contraction_hierarchy ? CchRouter(net_).route_all(router, requests_, threads)
                                           : router.route_all(requests_, threads);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  for (size_t i = 0; i < pending_.size(); ++i) {
    if (paths[i].empty()) {
      routes_.set_broken(pending_[i].slot, pending_[i].loc, "no route " + pending_[i].description);
    } else {
      routes_.set_resolved(pending_[i].slot, paths[i]);
    }
  }
  return seconds;
}

}  // namespace lpsim
