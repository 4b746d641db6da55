#pragma once
// What a driver (a co-simulation, a remote control) asks of the vehicles of a run between steps: add a
// vehicle, give one a new route, remove one (vehicle_commands.cpp). A driver queues them while the run stands
// (CommandQueue); Simulation::apply_commands applies them at the step boundary, in order, in every part of a
// partitioned run, and says what became of each. Each command is checked where the vehicle is (the part
// that has it on the road or in an insertion queue) and then applied everywhere the run keeps its trip.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "backends/stepper.hpp"
#include "demand/trip_table.hpp"
#include "engine/boundary_link.hpp"
#include "engine/host_books.hpp"
#include "engine/state_archive.hpp"
#include "engine/vehicle_query.hpp"
#include "net/network.hpp"
#include "transport/transport.hpp"

namespace lpsim {

struct VehicleCommand {
  enum class Kind : uint8_t { Add, SetRoute, Remove };
  Kind kind = Kind::Add;
  uint32_t vehicle = 0;         // SetRoute, Remove: the trip's index
  std::vector<uint32_t> edges;  // SetRoute: the new route, from the edge the vehicle is on or queued at
  NewTrip trip;                 // Add

  static VehicleCommand add(NewTrip trip);
  static VehicleCommand set_route(uint32_t vehicle, std::vector<uint32_t> edges);
  static VehicleCommand remove(uint32_t vehicle);

  /// Field by field (engine/state_archive.hpp): part 0 hands the commands to the other parts so.
  template <class A>
  void visit_state(A& a) {
    std::vector<char> id(trip.id.begin(), trip.id.end());
    a(kind);
    a(vehicle);
    a(edges);
    a(id);
    a(trip.type);
    a(trip.depart);
    a(trip.route);
    a(trip.speed_factor);
    a(trip.departure);
    if constexpr (A::kReads) trip.id.assign(id.begin(), id.end());
  }
};

/// What became of a command: the trip it concerns (Add: the new trip's index), or why it was refused.
struct CommandOutcome {
  uint32_t vehicle = 0;
  std::string error;  // empty: done
  bool done() const { return error.empty(); }
};

/// Commands a driver gives between steps, taken together at the step boundary.
class CommandQueue {
 public:
  void push(VehicleCommand c) { queued_.push_back(std::move(c)); }
  bool empty() const { return queued_.empty(); }
  std::vector<VehicleCommand> take() {
    std::vector<VehicleCommand> out;
    out.swap(queued_);
    return out;
  }

 private:
  std::vector<VehicleCommand> queued_;
};

/// The commands as bytes and back (part 0 hands them to the other parts).
Bytes command_bytes(const std::vector<VehicleCommand>& commands);
std::vector<VehicleCommand> commands_from_bytes(const Bytes& bytes);

/// What the commands reach of the run they act on, between steps (each outlives the applier).
struct CommandScope {
  const Network& net;
  TripTable& trips;
  HostBooks& books;
  Stepper& stepper;
  BoundaryLink& link;
  int map;                           // the lane map the state is in (the next step reads it)
  double now;                        // s
  double step_length;                // s
  std::function<void()> sync_trips;  // hands the backend the trip table as it lies now
};

/// One part's side of a batch of commands: each is first checked here (a verdict that says whether this part
/// has the vehicle and, if so, whether the command can act on it), the parts' verdicts are combined into the
/// command's outcome (combine_verdicts), and a command done is then applied in every part (apply).
class CommandApplier {
 public:
  /// `query`: the vehicles' state as the batch found it, fetched once for the whole batch; what the batch's
  /// own commands changed of it since is kept here.
  CommandApplier(const CommandScope& run, const VehicleQuery& query) : run_(run), query_(query) {}

  /// This part's verdict on `c`, as bytes: whether it has the vehicle, why the command cannot act on it, and
  /// what a removal erases of it from the lane map.
  Bytes verdict(const VehicleCommand& c) const;
  /// The command's outcome from every part's verdict (in part order).
  static CommandOutcome combine_verdicts(const VehicleCommand& c, const std::vector<Bytes>& verdicts,
                                         const Demand& demand);
  /// Applies a command that is done here: the trip table in every part, the vehicle's slot, queue entry or
  /// account where it is. `verdicts`: every part's, as combine_verdicts saw them.
  void apply(const VehicleCommand& c, const std::vector<Bytes>& verdicts);

 private:
  struct Where;
  Where locate(uint32_t v) const;
  std::string route_refusal(uint32_t v, const std::vector<uint32_t>& edges, const Where& at) const;

  CommandScope run_;
  const VehicleQuery& query_;
  // Vehicles on the road that an earlier command of the batch removed, or gave a new route (route
  // position 0 from then on), which the query, fetched before, does not show.
  std::vector<uint32_t> removed_, rerouted_;
};

}  // namespace lpsim
