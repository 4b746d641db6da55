#include "demand/trip_table.hpp"

#include <algorithm>
#include <stdexcept>

#include "demand/departure.hpp"

namespace lpsim {

TripTable::TripTable(Demand demand)
    : d_(std::move(demand)), loaded_trips_(d_.size()), loaded_route_edges_(d_.route_edges.size()) {
  changes_.first_new_vehicle = d_.size();
  changes_.first_new_route_edge = d_.route_edges.size();
}

bool TripTable::changed() const {
  return d_.size() > changes_.first_new_vehicle || d_.route_edges.size() > changes_.first_new_route_edge ||
         !changes_.new_routes.empty() || changes_.stops_moved;
}

bool TripTable::connected(const Network& net, const std::vector<uint32_t>& edges, uint32_t vclass) {
  for (size_t i = 0; i < edges.size(); ++i) {
    if ((net.edge_permissions[edges[i]] & vclass) == 0) return false;
    if (i + 1 < edges.size() && !net.connected(edges[i], edges[i + 1], vclass)) return false;
  }
  return true;
}

const std::unordered_map<std::string, uint32_t>& TripTable::index() const {
  if (index_.empty())
    for (uint32_t v = 0; v < d_.size(); ++v) index_.emplace(d_.vehicle_id[v], v);
  return index_;
}

int64_t TripTable::find(const std::string& id) const {
  const auto it = index().find(id);
  return it == index_.end() ? -1 : int64_t{it->second};
}

uint32_t TripTable::add(const NewTrip& t, const Network& net) {
  auto refuse = [&](const std::string& why) {
    throw std::invalid_argument("vehicle '" + t.id + "' cannot be added: " + why);
  };
  if (index().count(t.id)) refuse("the id is in use");
  if (t.type >= d_.types.size()) refuse("unknown vehicle type " + std::to_string(t.type));
  if (t.route.empty()) refuse("empty route");
  for (const uint32_t e : t.route)
    if (e >= net.num_edges() || net.edge_is_internal[e]) refuse("no normal edge " + std::to_string(e));
  if (net.edge_num_lanes[t.route.front()] == 0) refuse("its first edge has no vehicle lane");
  if (!connected(net, t.route, d_.types.vclass_mask[t.type]))
    refuse("its route is not connected for its vClass " + d_.types.vclass[t.type]);
  if (d_.size() >= 0x40000000u) refuse("too many vehicles");

  const DepartSpec& ds = t.departure;
  if (ds.lane == DepartLane::Given && car_lane_position(net, t.route.front(), ds.lane_index) < 0)
    refuse("departLane " + std::to_string(ds.lane_index) + " is not a vehicle lane of its first edge");

  const uint32_t v = d_.size();
  for (auto* c : {&d_.depart_lane_kind, &d_.depart_pos_kind, &d_.depart_speed_kind, &d_.arrival_pos_kind})
    c->push_back(0);
  d_.depart_lane.push_back(0);
  for (auto* c : {&d_.depart_pos, &d_.depart_speed, &d_.arrival_pos}) c->push_back(0);
  set_departure(d_, v, ds, net, t.route.front(), t.route.back());
  index_.emplace(t.id, v);
  d_.vehicle_id.push_back(t.id);
  d_.vehicle_type.push_back(t.type);
  d_.depart.push_back(t.depart);
  d_.route_begin.push_back(static_cast<uint32_t>(d_.route_edges.size()));
  d_.route_length.push_back(static_cast<uint32_t>(t.route.size()));
  d_.route_edges.insert(d_.route_edges.end(), t.route.begin(), t.route.end());
  d_.speed_factor.push_back(t.speed_factor);
  d_.source.push_back(DemandSource::Added);
  // An added trip makes no scheduled stops.
  if (!d_.stops.vehicle_begin.empty()) d_.stops.vehicle_begin.push_back(d_.stops.size());
  return v;
}

void TripTable::set_route(uint32_t v, const std::vector<uint32_t>& edges) {
  if (v < loaded_trips_) replaced_.try_emplace(v, LoadedRoute{d_.route_begin[v], d_.route_length[v]});
  d_.route_begin[v] = static_cast<uint32_t>(d_.route_edges.size());
  d_.route_length[v] = static_cast<uint32_t>(edges.size());
  d_.route_edges.insert(d_.route_edges.end(), edges.begin(), edges.end());
  if (v < changes_.first_new_vehicle) changes_.new_routes.push_back(v);
}

void TripTable::set_stop_positions(uint32_t v, const std::vector<uint32_t>& route_pos) {
  const uint32_t first = d_.stops.first(v);
  if (route_pos.size() != d_.stops.last(v) - first)
    throw std::invalid_argument("vehicle '" + d_.vehicle_id[v] + "': " + std::to_string(route_pos.size()) +
                                " stop positions for " + std::to_string(d_.stops.last(v) - first) + " stops");
  std::copy(route_pos.begin(), route_pos.end(), d_.stops.route_pos.begin() + first);
  changes_.stops_moved = true;
}

TripTable::Changes TripTable::take_changes() {
  Changes c = std::move(changes_);
  changes_ = Changes{};
  changes_.first_new_vehicle = d_.size();
  changes_.first_new_route_edge = d_.route_edges.size();
  return c;
}

}  // namespace lpsim
