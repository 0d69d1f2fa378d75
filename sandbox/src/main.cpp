// sandbox: the command-line program. Exit codes: 0 done, 2 bad input, 1 failure inside.
#include <CLI/CLI.hpp>

#include "commands.hpp"

#include <deform/error.hpp>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

int main(int argc, char** argv) {
  CLI::App app{"Real-time vehicle deformation sandbox"};
  app.require_subcommand(1);
  sandbox::registerMeshCommands(app);
  sandbox::registerBenchCommands(app);
  sandbox::registerFiguresCommand(app);
  sandbox::registerRunCommand(app);
  sandbox::registerExportCommand(app);
  sandbox::registerStressCommand(app);
  sandbox::registerTradeoffCommand(app);
  sandbox::registerConvergeCommand(app);
  sandbox::registerSweepCommand(app);
  // CLI11 says only "A subcommand is required" for a mistyped command; name it instead.
  const auto known =
      app.get_subcommands([&](const CLI::App* sub) { return argc > 1 && sub->get_name() == argv[1]; });
  if (argc > 1 && argv[1][0] != '-' && known.empty()) {
    std::string names;
    for (const CLI::App* sub : app.get_subcommands({}))
      names += (names.empty() ? "" : ", ") + sub->get_name();
    std::fprintf(stderr, "sandbox: unknown command '%s' (commands: %s)\n", argv[1], names.c_str());
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  } catch (const deform::InputError& e) {
    std::fprintf(stderr, "sandbox: %s\n", e.what());
    return 2;
  } catch (const std::filesystem::filesystem_error& e) {
    // A path the system cannot use (a name over 255 bytes, no permission, not a folder) is the user's to
    // change; what() names the operation, the path and the reason.
    std::fprintf(stderr, "sandbox: %s\n", e.what());
    return 2;
  } catch (const sandbox::CommandFailure& e) {
    std::fprintf(stderr, "sandbox: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sandbox: internal failure: %s\n", e.what());
    return 1;
  }
  return 0;
}
