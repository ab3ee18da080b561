// alloycolor: optical constants, reflectance and colour of binary metal alloys at any
// composition. Errors print one line (control characters shown as '?', cut at 300
// characters) and exit with status 2, out-of-memory included; 3 is kept for a bug. A
// closed standard output (`alloycolor sweep | head`) ends the run quietly with status 0.
// SIGINT, SIGTERM and SIGHUP remove the temporary of a file being written; SIGPIPE and
// SIGXFSZ are ignored, so a closed pipe or a file past `ulimit -f` is one error line
// naming the output (output_guard.h).
#include <poll.h>
#include <sys/stat.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <new>
#include <nlohmann/json.hpp>
#include <string>

#if __has_include(<glog/logging.h>)
#include <glog/logging.h>  // Ceres logs through glog
#define ALLOYCOLOR_HAVE_GLOG 1
#endif

#include "alloycolor/core/error.h"
#include "alloycolor/core/text.h"
#include "common.h"
#include "output_guard.h"

namespace {

void PrintError(const std::string& what, const char* kind = "error") {
  std::cerr << "alloycolor: " << kind << ": " << alloycolor::MessageLine(what) << "\n";
}

// True when standard output is a pipe or socket whose reader has gone.
bool StdoutReaderGone() {
  struct stat info;
  if (fstat(STDOUT_FILENO, &info) != 0) return false;
  if (!S_ISFIFO(info.st_mode) && !S_ISSOCK(info.st_mode)) return false;
  pollfd poll_fd{STDOUT_FILENO, POLLOUT, 0};
  return poll(&poll_fd, 1, 0) > 0 && (poll_fd.revents & POLLERR) != 0;
}

// The one line for a command line CLI11 refused, when it can name what was meant: an
// option the command does not take, with the command's nearest option ("--angel": did
// you mean --angle?), or a command that does not exist, with the nearest command; ""
// otherwise (CLI11's own message is printed then).
std::string GuidingLine(const CLI::App& app, int argc, char** argv) {
  const std::vector<CLI::App*> parsed = app.get_subcommands();
  if (parsed.empty()) {
    if (argc < 2 || argv[1][0] == '-') return "";
    std::vector<std::string> commands;
    for (const CLI::App* cmd : app.get_subcommands([](const CLI::App*) { return true; })) {
      commands.push_back(cmd->get_name());
    }
    if (std::find(commands.begin(), commands.end(), argv[1]) != commands.end()) return "";
    const std::string nearest = alloycolor::NearestName(argv[1], commands);
    std::string list;
    for (const std::string& name : commands) list += (list.empty() ? "" : ", ") + name;
    return "unknown command " + alloycolor::Quote(argv[1]) +
           (nearest.empty() ? "" : "; did you mean " + nearest + "?") + " (commands: " + list + ")";
  }
  const CLI::App* cmd = parsed.front();
  std::vector<std::string> names;  // long option names without their dashes
  for (const CLI::Option* option : cmd->get_options()) {
    for (const std::string& name : option->get_lnames()) names.push_back(name);
  }
  const int start = static_cast<int>(std::find(argv + 1, argv + argc, cmd->get_name()) - argv);
  for (int i = start + 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--") break;
    if (arg.size() < 3 || arg.compare(0, 2, "--") != 0) continue;
    const std::string name = arg.substr(2, arg.find('=') - 2);
    if (std::find(names.begin(), names.end(), name) != names.end()) continue;
    const std::string nearest = alloycolor::NearestName(name, names);
    return cmd->get_name() + ": unknown option " + alloycolor::Quote("--" + name) +
           (nearest.empty() ? "" : "; did you mean --" + nearest + "?") + " (see 'alloycolor " +
           cmd->get_name() + " --help')";
  }
  return "";
}

// Every command's --out is checked for an existing folder while the command line is read,
// before any work (a fit, a report); validate's --out is the report folder itself, made
// when missing.
void CheckOutputFoldersFirst(CLI::App& app) {
  for (CLI::App* cmd : app.get_subcommands([](const CLI::App*) { return true; })) {
    if (cmd->get_name() == "validate") continue;
    for (CLI::Option* option : cmd->get_options()) {
      if (!option->check_lname("out")) continue;
      option->check(CLI::Validator(
          [](std::string& path) { return alloycolor::app::OutputFolderProblem(path); },
          "FILE in an existing folder"));
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  // The program's output policy: inputs noted, temporaries removed on signals, SIGPIPE and
  // SIGXFSZ turned into write errors.
  alloycolor::app::ProgramOutputGuard output_guard;
#ifdef ALLOYCOLOR_HAVE_GLOG
  // The solver's own log (warnings, covariance notes) is not the program's output: progress
  // goes through the progress callbacks, errors through one line.
  FLAGS_minloglevel = 3;  // FATAL only
  FLAGS_stderrthreshold = 3;
#endif
  CLI::App app{"alloycolor " ALLOYCOLOR_VERSION
               ": optical constants, reflectance and colour of binary metal alloys\n"
               "at any composition, from measurements at a few compositions.\n"
               "Compositions: atomic fractions of the system's first element (0.75),\n"
               "75at%, 75wt%, or a karat for gold alloys (18k).\n"
               "Bundled data sets: Au-Ag, Cu-Zn, Nb-Sn (give --data NAME or a folder/manifest)."};
  app.require_subcommand(1);
  app.set_version_flag("--version", ALLOYCOLOR_VERSION);
  app.footer("Run 'alloycolor COMMAND --help' for a command's options; docs/usage.md has more.");
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
  alloycolor::app::RegisterMatch(app);
  alloycolor::app::RegisterTolerance(app);
  alloycolor::app::RegisterSuggest(app);
  CheckOutputFoldersFirst(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // An unknown option is named first: it is often why a required one seems missing.
    if (const std::string line = GuidingLine(app, argc, argv); !line.empty()) {
      PrintError(line);
      return 2;
    }
    std::string what = e.what();
    for (char& c : what) {
      if (c == '\n') c = ' ';
    }
    PrintError(what + " (see --help)");
    return 2;
  } catch (const alloycolor::Error& e) {
    if (StdoutReaderGone()) return 0;
    PrintError(e.what());
    return 2;
  } catch (const std::bad_alloc&) {
    PrintError("out of memory (the input or the options ask for more than this machine has)");
    return 2;
  } catch (const nlohmann::json::exception& e) {
    PrintError(std::string("invalid JSON value: ") + e.what());
    return 2;
  } catch (const std::exception& e) {
    PrintError(e.what(), "internal error");
    return 3;
  }
  alloycolor::app::FlushWarnings();
  std::cout.flush();
  if (!std::cout) {
    if (StdoutReaderGone()) return 0;
    PrintError("cannot write standard output");
    return 2;
  }
  return 0;
}
