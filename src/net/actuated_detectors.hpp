#pragma once
// Where an actuated signal's induction loops lie and which phases each may extend, decided as SUMO 1.15's
// actuated logic decides them when it loads (MSActuatedTrafficLightLogic::init); see docs/MODELS.md.
#include "net/network.hpp"

namespace lpsim {

/// Fills net's signal_det_begin, det_lane, det_pos, phase_det_begin and phase_det from its signals,
/// phases and connections (every signal and phase gets its range; only actuated ones get loops).
void place_actuated_detectors(Network& net);

}  // namespace lpsim
