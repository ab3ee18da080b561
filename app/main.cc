// alloycolor: optical constants, reflectance and colour of binary metal alloys at any
// composition. Errors print one line and exit with status 2.
#include <cstdio>
#include <iostream>

#include <CLI/CLI.hpp>

#include "alloycolor/core/error.h"
#include "common.h"

int main(int argc, char** argv) {
  CLI::App app{
      "alloycolor " ALLOYCOLOR_VERSION
      ": optical constants, reflectance and colour of binary metal alloys at any "
      "composition, from measurements at a few compositions.\n"
      "Compositions are atomic fractions of the system's first element (0.75), or "
      "75at%, 75wt%, or a karat for gold alloys (18k).\n"
      "Bundled data sets: Au-Ag, Cu-Zn, Nb-Sn (give --data NAME or a folder/manifest)."};
  app.require_subcommand(1);
  app.set_version_flag("--version", ALLOYCOLOR_VERSION);
  app.footer("Run 'alloycolor COMMAND --help' for a command's options.");
  alloycolor::app::RegisterColor(app);
  alloycolor::app::RegisterFit(app);
  alloycolor::app::RegisterPredict(app);
  alloycolor::app::RegisterRender(app);
  alloycolor::app::RegisterExport(app);
  alloycolor::app::RegisterValidate(app);
  alloycolor::app::RegisterChart(app);
  alloycolor::app::RegisterParams(app);
  alloycolor::app::RegisterSweep(app);
  alloycolor::app::RegisterExplore(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::string what = e.what();
    for (char& c : what) {
      if (c == '\n') c = ' ';
    }
    std::cerr << "alloycolor: error: " << what << " (see --help)\n";
    return 2;
  } catch (const alloycolor::Error& e) {
    std::cerr << "alloycolor: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "alloycolor: internal error: " << e.what() << "\n";
    return 3;
  }
  alloycolor::app::FlushWarnings();
  std::cout.flush();
  if (!std::cout) {
    std::cerr << "alloycolor: error: cannot write standard output\n";
    return 2;
  }
  return 0;
}
