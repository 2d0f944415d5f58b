#include "app/program.hpp"

#include <memory>

#include "app/cli.hpp"
#include "app/exit_codes.hpp"

namespace particles::app {

int runProgram(const std::vector<std::string>& args) {
  auto cli = std::make_unique<Cli>();
  try {
    cli->parse(args);
  } catch (const CLI::ParseError& e) {
    const int code = cli->app.exit(e);  // prints help, the version or the error
    return code == 0 ? kOk : kBadInput;
  }
  return cli->dispatch(args);
}

}  // namespace particles::app
