// uwgrasp config: prints the effective configuration as YAML (a starting point for --config).
#include <iostream>

#include "app/common.hpp"
#include "commands.hpp"

namespace uwgrasp::app {

void add_config_command(CLI::App& app, std::vector<std::pair<CLI::App*, Runner>>& runners) {
  auto* cmd = app.add_subcommand("config", "Print the effective configuration as YAML");
  auto opt = std::make_shared<CommonOptions>();
  add_common(*cmd, *opt);
  runners.emplace_back(cmd, [opt] {
    const Session s = open_session(*opt);
    std::cout << io::to_yaml(s.config);
    return 0;
  });
}

}  // namespace uwgrasp::app
