#pragma once
#include "core/net_spec.hpp"
#include "net/network.hpp"

namespace lpsim {

/// Fills Network::conn_foe_begin/conn_foe from the junctions' <request> rows: connection c yields to every
/// connection whose junction link index has its bit set in c's response. A connection's junction link
/// index is the position of its internal lane in the junction's intLanes (the second internal lane for
/// links with an internal junction); in nets without internal lanes it is the connection's rank at the
/// junction (incoming lanes in incLanes order, each lane's links in file order).
/// Connections without a response row yield to nobody. Clears conn_keep_clear of connections whose row
/// names no foes.
void build_junction_foes(const NetSpec& spec, Network& net);

}  // namespace lpsim
