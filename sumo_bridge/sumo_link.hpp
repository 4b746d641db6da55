#pragma once
// A running SUMO that the co-simulation drives: in this process through libsumo (Debian's libsumocpp), or a
// `sumo`/`sumo-gui` process over a TraCI socket (libtracicpp). The bridge needs the same few calls of both;
// each call's failure (SUMO refused it, or died) is a SumoError naming the call.
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace lpsim {

enum class SumoMode { Libsumo, Traci };

struct SumoError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// A signal (SIGINT, SIGTERM, SIGHUP) came while a SUMO process was still starting: the start was given up.
struct SumoStartInterrupted : SumoError {
  using SumoError::SumoError;
};

/// A vehicle handed into SUMO: it enters at `pos` metres of lane `lane` of route.front() at up to `speed`
/// (lower where SUMO finds that speed unsafe there; its maximum speed is `speed` until restore_max_speed()),
/// then drives the rest of the route. With lane -1 it departs there as a trip does, by SUMO's depart
/// attributes (departLane, departPos, departSpeed values).
struct SumoEntry {
  std::string id, type;
  std::vector<std::string> route;  // SUMO edge ids, each reachable from the one before
  int lane = 0;
  double pos = 0, speed = 0;
  std::string depart_lane = "first", depart_pos = "base", depart_speed = "0";  // lane -1 only
  double speed_factor = 0;          // > 0: the vehicle's own (as the other side drew it); else SUMO draws one
  std::string arrival_pos = "max";  // SUMO's arrivalPos on the route's last edge
  double depart = -1;               // s: the SUMO step that is to insert it (< 0: SUMO's next)
  // Scheduled stops SUMO is to make on the way (an edge of `route`; until < 0: none; duration <= 0: until).
  struct Stop {
    std::string edge;
    int lane = 0;
    double start = 0, end = 0, duration = 0, until = -1;
  };
  std::vector<Stop> stops{};
};

/// Where a vehicle is in SUMO.
struct SumoVehicle {
  std::string edge;  // SUMO's road id (an internal edge's starts with ':')
  int lane = 0;
  double pos = 0, speed = 0;
  int route_index = 0;  // of its current (or, on an internal edge, last) edge in the route SUMO drives
  // SUMO no longer has it, and did not list it among its arrivals: it teleported beyond its route's last
  // edge (SUMO 1.15 removes such a vehicle without reporting it as arrived).
  bool gone = false;
};

class SumoLink {
 public:
  virtual ~SumoLink() = default;
  virtual SumoMode mode() const = 0;
  /// The SUMO process's id over TraCI (0 in process): what a fault test stops or kills.
  virtual int process_id() const = 0;
  /// SUMO's version string ("SUMO 1.15.0").
  virtual std::string version() = 0;
  /// SUMO's step length and time, s.
  virtual double step_length() = 0;
  virtual double time() = 0;
  /// Runs SUMO's steps up to time t (the first step boundary at or after it).
  virtual void step_to(double t) = 0;
  /// Adds a vehicle (an id in use is a SumoError). It is inserted in SUMO's next step where its insertion
  /// checks pass, else it stays pending (pending()).
  virtual void add(const SumoEntry& entry) = 0;
  /// Vehicles added and not yet inserted.
  virtual std::vector<std::string> pending() = 0;
  /// Vehicles that ended their route in SUMO's last step (those remove() took out are not among them).
  virtual std::vector<std::string> arrived() = 0;
  virtual SumoVehicle vehicle(const std::string& id) = 0;
  /// Vehicles inserted in SUMO's last step.
  virtual std::vector<std::string> departed() = 0;
  /// From now on watched() reports where the running vehicle `id` is, until it arrives or is removed (over
  /// TraCI a subscription, so that one call per step reads them all; in process, getters).
  virtual void watch(const std::string& id) = 0;
  /// Where every watched vehicle is after SUMO's last step, by id; one SUMO removed without an arrival is
  /// reported gone once, and no longer watched.
  virtual std::vector<std::pair<std::string, SumoVehicle>> watched() = 0;
  /// Takes a vehicle out of SUMO (running or pending), as a hand-over out of the corridor does; it is no
  /// longer watched.
  virtual void remove(const std::string& id) = 0;
  /// Gives a vehicle handed in on a lane its type's maximum speed back (once it has been inserted).
  virtual void restore_max_speed(const std::string& id, double max_speed) = 0;
  /// Holds a running vehicle: it brakes to a stop as its model allows, and stays until removed.
  virtual void hold(const std::string& id) = 0;
  /// Vehicles running in SUMO (inserted, not yet arrived or removed).
  virtual int running() = 0;
  /// Ends SUMO (it writes and closes its outputs). Idempotent; the destructor calls it.
  virtual void close() = 0;
};

/// Starts SUMO with `args` (its options, as on its command line): in this process (libsumo; `binary` is not
/// used, and only one libsumo simulation may run in a process at a time), or `binary` (a path, or a name
/// looked up on PATH: "sumo", "sumo-gui") as a process on a free local port. A SumoError when it cannot start
/// (binary missing, options or input files SUMO refuses). Over TraCI, a SUMO process that does not answer a
/// call within `answer_timeout_s` is killed and the call is a SumoError (in process, a call cannot hang
/// apart from this process). Sets SUMO_HOME to Debian's /usr/share/sumo when it is unset (SUMO needs its
/// schemas to read files that name one).
std::unique_ptr<SumoLink> start_sumo(SumoMode mode, const std::string& binary,
                                     const std::vector<std::string>& args, double answer_timeout_s = 300);

}  // namespace lpsim
