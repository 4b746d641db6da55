#pragma once
#include "converters/xml_stream.hpp"
#include "core/net_spec.hpp"

namespace lpsim {

/// Reads a <tlLogic> element and its <phase> children; `xs` must be at the tlLogic's Start event and is
/// left at its End event. Shared by the net reader and the add-file reader.
TlLogicSpec read_tl_logic(XmlStream& xs);

}  // namespace lpsim
