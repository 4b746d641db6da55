#include "converters/sumocfg_reader.hpp"

#include <filesystem>

#include "converters/cli_options.hpp"
#include "converters/xml_stream.hpp"

namespace lpsim {

ConfigSpec read_sumocfg(const std::string& path) {
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
    // themselves carry no value attribute. Options LPSim does not use are ignored, as the header says.
    auto value = xs.attr("value");
    if (!value) continue;
    where.loc = xs.loc();
    apply_option(config, xs.name(), *value, where);
  }
  return config;
}

}  // namespace lpsim
