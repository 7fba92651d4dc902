// shudder: command-line entry. Argument parsing and dispatch only; no physics here.
#include <CLI/CLI.hpp>

#include <iostream>

int main(int argc, char** argv) {
  CLI::App app{"shudder: stick-slip and shudder in wet-clutch drivetrains"};
  app.require_subcommand(1);
  CLI11_PARSE(app, argc, argv);
  return 0;
}
