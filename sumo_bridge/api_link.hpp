#pragma once
// SumoLink over one of SUMO's two C++ client libraries, which offer the same classes in two namespaces
// (libsumo:: in process, libtraci:: over a socket): Api names them (libsumo_link.cpp, traci_link.cpp). Every
// call's exception becomes a SumoError naming the call.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <utility>
#include <vector>

// The client libraries' shared types: results and variable codes are libsumo's in both.
#include <libsumo/TraCIConstants.h>
#include <libsumo/TraCIDefs.h>

#include "sumo_bridge/sumo_link.hpp"
#include "sumo_bridge/sumo_start.hpp"

namespace lpsim {

template <class Api>
class ApiLink final : public SumoLink {
 public:
  /// Over a SUMO already started and connected (in process: `process` null).
  explicit ApiLink(std::unique_ptr<SumoProcess> process) : process_(std::move(process)) {}
  ~ApiLink() override {
    try {
      close();
    } catch (const std::exception&) {
      // SUMO already gone: nothing left to close (the process, if any, is killed below).
    }
  }

  SumoMode mode() const override { return Api::kMode; }
  int process_id() const override { return process_ ? static_cast<int>(process_->pid()) : 0; }
  std::string version() override {
    return call("getVersion", [] { return Api::Simulation::getVersion().second; });
  }
  double step_length() override {
    return call("getDeltaT", [] { return Api::Simulation::getDeltaT(); });
  }
  double time() override {
    return call("getTime", [] { return Api::Simulation::getTime(); });
  }
  void step_to(double t) override {
    bool stale_subscription = false;
    call("simulationStep", [&] {
      try {
        Api::Simulation::step(t);
      } catch (const libsumo::TraCIException& e) {
        // SUMO 1.15 answers the subscription of a vehicle it removed without an arrival (one that teleported
        // beyond its route's end) with an error, once. The step itself ran; its subscription results are
        // incomplete.
        if (Api::kReadsDirectly || std::string(e.what()).rfind("Subscription response error", 0) != 0) throw;
        stale_subscription = true;
      }
    });
    if (stale_subscription) drop_stale_subscriptions();
  }

  void add(const SumoEntry& e) override {
    const std::string& first = e.route.front();
    // SUMO 1.15 cannot remove a route: one one-edge route per entry edge serves every vehicle entering there,
    // and setRoute gives each its own edges before it is inserted.
    const std::string route = "lpsim_entry_" + first;
    if (entry_routes_.insert(first).second)
      call("route.add " + route, [&] { Api::Route::add(route, {first}); });
    // A given departSpeed that SUMO finds unsafe (a junction too close to brake for) makes it drop the
    // vehicle with an error; "max" lets it lower the speed instead, and the vehicle's maximum speed, until it
    // is inserted (restore_max_speed), caps it at the speed it had.
    const bool capped = e.lane >= 0 && e.speed >= kLeastCappedSpeed;
    const std::string depart = e.depart >= 0 ? number(e.depart) : "now";
    call("vehicle.add " + e.id, [&] {
      if (e.lane < 0)
        Api::Vehicle::add(e.id, route, e.type, depart, e.depart_lane, e.depart_pos, e.depart_speed, "current",
                          e.arrival_pos);
      else
        Api::Vehicle::add(e.id, route, e.type, depart, std::to_string(e.lane), number(e.pos),
                          capped ? "max" : "0", "current", e.arrival_pos);
    });
    if (capped) call("vehicle.setMaxSpeed " + e.id, [&] { Api::Vehicle::setMaxSpeed(e.id, e.speed); });
    if (e.route.size() > 1) call("vehicle.setRoute " + e.id, [&] { Api::Vehicle::setRoute(e.id, e.route); });
    if (e.speed_factor > 0)
      call("vehicle.setSpeedFactor " + e.id, [&] { Api::Vehicle::setSpeedFactor(e.id, e.speed_factor); });
    for (const SumoEntry::Stop& s : e.stops)
      call("vehicle.setStop " + e.id, [&] {
        Api::Vehicle::setStop(
            e.id, s.edge, s.end, s.lane, s.duration > 0 ? s.duration : libsumo::INVALID_DOUBLE_VALUE,
            libsumo::STOP_DEFAULT, s.start, s.until >= 0 ? s.until : libsumo::INVALID_DOUBLE_VALUE);
      });
  }
  std::vector<std::string> pending() override {
    return call("getPendingVehicles", [] { return Api::Simulation::getPendingVehicles(); });
  }
  std::vector<std::string> arrived() override {
    std::vector<std::string> ids =
        call("getArrivedIDList", [] { return Api::Simulation::getArrivedIDList(); });
    for (const std::string& id : ids) {  // SUMO ends an arrived vehicle's subscription
      watched_.erase(id);
      gone_.erase(std::remove(gone_.begin(), gone_.end(), id), gone_.end());
    }
    return ids;
  }
  SumoVehicle vehicle(const std::string& id) override {
    return call("vehicle " + id, [&] { return read_vehicle(id); });
  }
  std::vector<std::string> departed() override {
    return call("getDepartedIDList", [] { return Api::Simulation::getDepartedIDList(); });
  }
  void watch(const std::string& id) override {
    if (!Api::kReadsDirectly)
      call("vehicle.subscribe " + id, [&] { Api::Vehicle::subscribe(id, kWatchedVariables); });
    watched_.insert(id);
  }
  std::vector<std::pair<std::string, SumoVehicle>> watched() override {
    std::vector<std::pair<std::string, SumoVehicle>> out;
    out.reserve(watched_.size());
    if (Api::kReadsDirectly) {  // in this process: a call cannot hang, and SUMO says which id it lacks
      for (auto it = watched_.begin(); it != watched_.end();) {
        try {
          out.emplace_back(*it, read_vehicle(*it));
          ++it;
        } catch (const libsumo::TraCIException&) {
          if (known(*it)) {
            out.emplace_back(*it, vehicle(*it));  // another failure: a SumoError naming it
            ++it;
            continue;
          }
          out.emplace_back(*it, gone());
          it = watched_.erase(it);
        }
      }
      return out;
    }
    if (!gone_.empty() || reread_) {  // this step's subscription results are incomplete: one call each
      for (const std::string& id : gone_) out.emplace_back(id, gone());
      gone_.clear();
      reread_ = false;
      for (const std::string& id : watched_) out.emplace_back(id, vehicle(id));
      return out;
    }
    const auto results =
        call("vehicle.getAllSubscriptionResults", [] { return Api::Vehicle::getAllSubscriptionResults(); });
    for (auto it = watched_.begin(); it != watched_.end();) {  // its subscription ended with it
      if (results.count(*it)) {
        ++it;
      } else {
        out.emplace_back(*it, gone());
        it = watched_.erase(it);
      }
    }
    for (const auto& [id, values] : results) {
      SumoVehicle v;
      for (const auto& [variable, value] : values) {
        if (!value) continue;
        if (variable == libsumo::VAR_ROAD_ID) v.edge = value->getString();
        if (variable == libsumo::VAR_LANE_INDEX) v.lane = as_int(*value);
        if (variable == libsumo::VAR_LANEPOSITION) v.pos = as_double(*value);
        if (variable == libsumo::VAR_SPEED) v.speed = as_double(*value);
        if (variable == libsumo::VAR_ROUTE_INDEX) v.route_index = as_int(*value);
      }
      out.emplace_back(id, std::move(v));
    }
    return out;
  }
  void remove(const std::string& id) override {
    // A removed vehicle that is still subscribed makes later steps fail (SUMO 1.15).
    if (watched_.erase(id) && !Api::kReadsDirectly)
      call("vehicle.unsubscribe " + id, [&] { Api::Vehicle::unsubscribe(id); });
    call("vehicle.remove " + id, [&] { Api::Vehicle::remove(id); });
  }
  void restore_max_speed(const std::string& id, double max_speed) override {
    call("vehicle.setMaxSpeed " + id, [&] { Api::Vehicle::setMaxSpeed(id, max_speed); });
  }
  void hold(const std::string& id) override {
    call("vehicle.setSpeed " + id, [&] { Api::Vehicle::setSpeed(id, 0.0); });
  }
  int running() override {
    return call("vehicle.getIDCount", [] { return Api::Vehicle::getIDCount(); });
  }
  void close() override {
    if (!open_) return;
    open_ = false;
    call("close", [] { Api::Simulation::close(); });
    if (process_) process_->finish(kCloseSeconds);
  }

 private:
  // Exactly the value, as SUMO parses attribute text (no locale, no rounding to six digits).
  static std::string number(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    return buf;
  }

  template <class F>
  auto call(const std::string& what, F f) -> decltype(f()) {
    std::optional<SumoProcess::Call> watched;
    if (process_) watched.emplace(*process_, process_->answer_timeout());
    try {
      return f();
    } catch (const std::exception& e) {
      watched.reset();
      const std::string who = Api::kMode == SumoMode::Libsumo ? "SUMO (libsumo)" : "SUMO (TraCI)";
      int status = 0;
      if (process_ && process_->timed_out())
        throw SumoError(who + " did not answer " + what + " within " + number(process_->answer_timeout()) +
                        " s: stopped");
      if (process_ && (process_->ended(&status) || wait_for_end(&status)))
        throw SumoError(who + " ended (status " + std::to_string(status) + ") during " + what);
      throw SumoError(who + " refused " + what + ": " + e.what());
    }
  }

  // A call that failed because SUMO is going away: the process ends a moment after its socket closes.
  bool wait_for_end(int* status) {
    for (int i = 0; i < 50; ++i) {
      if (process_->ended(status)) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
  }

  // The watched vehicles SUMO no longer has (SUMO ended their subscriptions with that error): watched()
  // reports them gone.
  void drop_stale_subscriptions() {
    const std::vector<std::string> ids = call("vehicle.getIDList", [] { return Api::Vehicle::getIDList(); });
    const std::set<std::string> running(ids.begin(), ids.end());
    for (auto it = watched_.begin(); it != watched_.end();) {
      if (running.count(*it)) {
        ++it;
        continue;
      }
      gone_.push_back(*it);
      it = watched_.erase(it);
    }
    reread_ = true;
  }
  static SumoVehicle read_vehicle(const std::string& id) {
    return SumoVehicle{Api::Vehicle::getRoadID(id), Api::Vehicle::getLaneIndex(id),
                       Api::Vehicle::getLanePosition(id), Api::Vehicle::getSpeed(id),
                       Api::Vehicle::getRouteIndex(id)};
  }
  bool known(const std::string& id) {
    const std::vector<std::string> ids = call("vehicle.getIDList", [] { return Api::Vehicle::getIDList(); });
    return std::find(ids.begin(), ids.end(), id) != ids.end();
  }
  static SumoVehicle gone() {
    SumoVehicle v;
    v.gone = true;
    return v;
  }
  static int as_int(const libsumo::TraCIResult& r) {
    const auto* i = dynamic_cast<const libsumo::TraCIInt*>(&r);
    return i != nullptr ? i->value : std::stoi(r.getString());
  }
  static double as_double(const libsumo::TraCIResult& r) {
    const auto* d = dynamic_cast<const libsumo::TraCIDouble*>(&r);
    return d != nullptr ? d->value : std::stod(r.getString());
  }

  inline static const std::vector<int> kWatchedVariables{libsumo::VAR_ROAD_ID, libsumo::VAR_LANE_INDEX,
                                                         libsumo::VAR_LANEPOSITION, libsumo::VAR_SPEED,
                                                         libsumo::VAR_ROUTE_INDEX};

  // Slower than this, a vehicle handed in enters standing.
  static constexpr double kLeastCappedSpeed = 0.1;
  // How long SUMO may take to write and close its outputs after the client closed it.
  static constexpr double kCloseSeconds = 60;

  std::unique_ptr<SumoProcess> process_;
  bool open_ = true;
  std::set<std::string> entry_routes_;
  std::set<std::string> watched_;
  std::vector<std::string> gone_;  // found gone after a step whose subscription results were incomplete
  bool reread_ = false;            // those results are incomplete
};

}  // namespace lpsim
