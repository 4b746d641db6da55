#include "converters/sumocfg_reader.hpp"

#include <filesystem>

#include "converters/cli_options.hpp"
#include "converters/xml_stream.hpp"

namespace lpsim {

ConfigSpec read_sumocfg(const std::string& path, SourceLoc* time_window_at) {
  XmlStream xs(path);
  ConfigSpec config;
  config.config_file = path;
  // SUMO resolves every file option of a configuration against the configuration's own folder.
  OptionSource where;
  where.base_dir = std::filesystem::path(path).parent_path().string();

  bool root_seen = false;
  for (;;) {
    auto ev = xs.next();
    if (ev == XmlStream::Event::Eof) break;
    if (ev != XmlStream::Event::Start) continue;
    if (!root_seen) {
      if (xs.name() != "configuration" && xs.name() != "sumoConfiguration")
        throw InputError(xs.loc(), "root element is <" + xs.name() +
                                       ">, expected <configuration> or <sumoConfiguration> of a SUMO config");
      root_seen = true;
      continue;
    }
    // Options sit in sections (<input>, <time>, ...) but are recognised by name wherever they are; sections
    // themselves carry no value attribute. SUMO refuses a name it does not know, and so does LPSim.
    auto value = xs.attr("value");
    if (!value) continue;
    where.loc = xs.loc();
    if (!apply_option(config, xs.name(), *value, where))
      throw InputError(where.loc, "<" + xs.name() +
                                      ">: unknown option (neither a SUMO option nor one LPSim reads "
                                      "from a .sumocfg)");
    if (time_window_at && (xs.name() == "begin" || xs.name() == "end")) *time_window_at = where.loc;
  }
  return config;
}

}  // namespace lpsim
