#include "converters/tl_logic_reader.hpp"

namespace lpsim {

TlLogicSpec read_tl_logic(XmlStream& xs) {
  TlLogicSpec tl;
  tl.loc = xs.loc();
  tl.id = xs.required("id");
  tl.program_id = xs.get("programID", "0");
  tl.type = xs.get("type", "static");
  tl.offset = xs.number("offset", 0);
  const int depth = xs.depth();
  for (;;) {
    auto ev = xs.next();
    if (ev == XmlStream::Event::Eof) xs.fail("unexpected end of file inside <tlLogic id=\"" + tl.id + "\">");
    if (ev == XmlStream::Event::End && xs.depth() == depth) break;
    if (ev == XmlStream::Event::Start && xs.name() == "param") {
      tl.params.emplace_back(xs.required("key"), xs.get("value", ""));
      continue;
    }
    if (ev != XmlStream::Event::Start || xs.name() != "phase") continue;
    PhaseSpec ph;
    ph.duration = xs.required_number("duration");
    if (ph.duration <= 0) xs.fail("phase duration must be positive: " + xs.required("duration"));
    ph.state = xs.required("state");
    ph.min_dur = xs.non_negative("minDur", -1);
    ph.max_dur = xs.non_negative("maxDur", -1);
    ph.name = xs.get("name", "");
    for (char c : ph.state)
      if (std::string_view("rRyYgGsuoO").find(c) == std::string_view::npos)
        xs.fail(std::string("unknown signal state '") + c + "' in phase state '" + ph.state + "'");
    ph.loc = xs.loc();
    tl.phases.push_back(std::move(ph));
  }
  if (tl.phases.empty()) throw InputError(tl.loc, "<tlLogic id=\"" + tl.id + "\">: no phases");
  return tl;
}

}  // namespace lpsim
