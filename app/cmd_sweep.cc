// alloycolor sweep: the colour of an alloy at N evenly spaced compositions, as CSV or JSON,
// fast enough for millions of rows (render/sweep.h; output formatted into blocks), all or
// nothing: the rows stream through a StreamOutput (core/output.h), so a sweep that fails
// half-way shows no row, whatever its size, in bounded memory. Its size is known before
// the work: past 1 GB (kMaxOutputBytes, the ceiling every command keeps) it is refused
// unless --force, and said on stderr when forced; the file system that will hold it
// (or the size limit for files) must have room for it; a long sweep shows its progress.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/color/material_color.h"
#include "alloycolor/color/sweep.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/json.h"
#include "alloycolor/core/output.h"
#include "alloycolor/core/parallel.h"
#include "alloycolor/core/text.h"
#include "common.h"

namespace alloycolor::app {
namespace {

constexpr long long kMaxSteps = 1000000000;

// The most a command writes without --force: 1 GB.
constexpr unsigned long long kMaxOutputBytes = 1000000000ULL;
// What a row takes, on average (measured over 100,000 rows of the bundled sets: 77.5 bytes
// in CSV, 110.5 in JSON), and the head and tail around the rows, at most.
constexpr double kCsvRowBytes = 78.0;
constexpr double kJsonRowBytes = 111.0;
constexpr unsigned long long kHeadBytes = 1000;
// Sweeps of at least this many rows report their progress every tenth of the way.
constexpr long long kProgressMinSteps = 10000000;

struct SweepOptions {
  ModelSource source;
  std::string from_text, to_text;
  long long steps = 101;
  double angle_deg = 0.0;
  std::string illuminant = "D65";
  int observer = 2;
  std::string format = "csv";
  bool exact = false;
  bool sigma = false;
  bool force = false;
  bool quiet = false;
  std::string out;  // empty: standard output
};

// Text formatted without stdio into blocks of 1 MiB, each handed to the StreamOutput.
class Output {
 public:
  explicit Output(StreamOutput* stream) : stream_(stream) { buffer_.resize(kBlock + kSlack); }
  ~Output() = default;

  void Text(std::string_view text) {
    if (used_ + text.size() > buffer_.size()) {
      Flush();
      if (text.size() > buffer_.size()) buffer_.resize(text.size());
    }
    std::memcpy(buffer_.data() + used_, text.data(), text.size());
    used_ += text.size();
  }
  void Char(char c) { buffer_[used_++] = c; }

  // |value| rounded to `decimals` (at most 9) digits after the point, like %.*f; with
  // trim, trailing zeros after the first decimal are dropped.
  void Fixed(double value, int decimals, bool trim = false) {
    static constexpr std::uint64_t kPow10[] = {1,      10,      100,      1000,      10000,
                                               100000, 1000000, 10000000, 100000000, 1000000000};
    const double scaled = std::abs(value) * static_cast<double>(kPow10[decimals]);
    if (!(scaled < 9e15)) {  // huge or not finite: rare, through snprintf
      char text[400];
      const int n = std::snprintf(text, sizeof text, "%.*f", decimals, value);
      Text(std::string_view(text, n > 0 ? std::min<size_t>(n, sizeof text - 1) : 0));
      return;
    }
    const auto rounded = static_cast<std::uint64_t>(scaled + 0.5);
    if (value < 0 && rounded != 0) Char('-');
    Unsigned(rounded / kPow10[decimals]);
    if (decimals == 0) return;
    std::uint64_t fraction = rounded % kPow10[decimals];
    char digits[9];
    for (int i = decimals - 1; i >= 0; --i) {
      digits[i] = static_cast<char>('0' + fraction % 10);
      fraction /= 10;
    }
    int keep = decimals;
    if (trim) {
      while (keep > 1 && digits[keep - 1] == '0') --keep;
    }
    Char('.');
    std::memcpy(buffer_.data() + used_, digits, keep);
    used_ += keep;
  }

  void Unsigned(std::uint64_t value) {
    char digits[20];
    int n = 0;
    do {
      digits[n++] = static_cast<char>('0' + value % 10);
      value /= 10;
    } while (value != 0);
    while (n > 0) buffer_[used_++] = digits[--n];
  }

  // Call between rows: flushes when the block is full.
  void EndRow() {
    if (used_ >= kBlock) Flush();
  }

  void Flush() {
    if (used_ > 0) stream_->Write(buffer_.data(), used_);
    used_ = 0;
  }

 private:
  static constexpr size_t kBlock = 1 << 20;
  static constexpr size_t kSlack = 4096;  // room for one row past the block
  StreamOutput* stream_;
  std::vector<char> buffer_;
  size_t used_ = 0;
};

std::string Describe(double x) {
  std::ostringstream out;
  out << x;
  return out.str();
}

// The JSON output's head (its results follow) or the CSV's header line; `table`: the
// interpolated table the rows come from, null where each is evaluated.
void WriteHead(Output& out, const SweepOptions& o, const AlloyModel& model,
               const std::string& illuminant, const color::ColorSweep* table) {
  if (o.format == "json") {
    nlohmann::json head = {{"system", model.system().Name()},
                           {"method", model.method()},
                           {"composition", "atomic_fraction_a"},
                           {"illuminant", illuminant},
                           {"observer", o.observer},
                           {"angle_deg", o.angle_deg},
                           {"steps", o.steps}};
    head["evaluation"] = table ? nlohmann::json{{"method", "table"},
                                                {"nodes", table->table_nodes()},
                                                {"max_error_xyz", table->table_error()},
                                                {"tolerance_xyz", color::kSweepTableTolerance}}
                               : nlohmann::json{{"method", "exact"}};
    std::string text = JsonText(head);
    text.pop_back();  // the closing brace; the results follow
    out.Text(text);
    out.Text(",\"results\":[\n");
  } else {
    out.Text(o.sigma ? "x,X,Y,Z,L,a,b,srgb8_r,srgb8_g,srgb8_b,sigma_de00\n"
                     : "x,X,Y,Z,L,a,b,srgb8_r,srgb8_g,srgb8_b\n");
  }
}

// One row: x, XYZ, L*a*b*, sRGB and, where given, the one-sigma ΔE00.
void WriteRow(Output& out, bool json, bool first, double x, const color::XYZ& xyz,
              const color::XYZ& white, const double* sigma) {
  const color::Lab lab = color::LabFromXYZ(xyz, white);
  const auto rgb = color::SRGB8FromLinear(color::LinearSRGBFromXYZ(xyz));
  if (json) {
    out.Text(first ? "{\"x\":" : ",\n{\"x\":");
    out.Fixed(x, 9, true);
    out.Text(",\"XYZ\":[");
  } else {
    out.Fixed(x, 9, true);
    out.Char(',');
  }
  out.Fixed(xyz.X, 7);
  out.Char(',');
  out.Fixed(xyz.Y, 7);
  out.Char(',');
  out.Fixed(xyz.Z, 7);
  out.Text(json ? "],\"Lab\":[" : ",");
  out.Fixed(lab.L, 4);
  out.Char(',');
  out.Fixed(lab.a, 4);
  out.Char(',');
  out.Fixed(lab.b, 4);
  out.Text(json ? "],\"srgb8\":[" : ",");
  out.Unsigned(rgb[0]);
  out.Char(',');
  out.Unsigned(rgb[1]);
  out.Char(',');
  out.Unsigned(rgb[2]);
  if (sigma) {
    out.Text(json ? "],\"sigma_de00\":" : ",");
    out.Fixed(*sigma, 4);
    out.Text(json ? "}" : "\n");
  } else {
    out.Text(json ? "]}" : "\n");
  }
}

// The options, and the output's size before the work: refused past the ceiling unless
// --force, and only where there is room for it.
struct SweepSize {
  unsigned long long bytes;
  std::string text;
};

SweepSize CheckSweep(const SweepOptions& o) {
  if (o.format != "csv" && o.format != "json") {
    throw Error("--format: '" + o.format + "' is not csv or json");
  }
  if (o.steps < 1 || o.steps > kMaxSteps) {
    throw Error("--steps: " + std::to_string(o.steps) + " is not between 1 and " +
                std::to_string(kMaxSteps));
  }
  CheckAngleDeg("--angle", o.angle_deg);
  const double row_bytes = o.format == "json" ? kJsonRowBytes : kCsvRowBytes;
  const auto estimate =
      static_cast<unsigned long long>(static_cast<double>(o.steps) * row_bytes) + kHeadBytes;
  const std::string size_text =
      std::to_string(o.steps) + " rows, about " + ByteSizeText(estimate) + " of " + o.format;
  if (estimate > kMaxOutputBytes && !o.force) {
    throw Error("--steps " + std::to_string(o.steps) + ": the sweep would write " + size_text +
                ", past the " + ByteSizeText(kMaxOutputBytes) +
                " a command writes without --force; give fewer --steps, or --force to write it");
  }
  if (!o.out.empty()) CheckOutputPath(o.out);
  CheckOutputRoom(o.out, estimate);
  return {estimate, size_text};
}

void Run(const SweepOptions& o) {
  const SweepSize size = CheckSweep(o);
  const ProgressCallback progress = ProgressPrinter(o.quiet);
  if (size.bytes > kMaxOutputBytes) {
    Report(progress, "sweep: writing " + size.text + " to " +
                         (o.out.empty() ? std::string("standard output") : o.out) + " (--force)");
  }
  const color::Colorimeter colorimeter = LoadColorimeter(o.illuminant, o.observer);
  if (o.from_text.find(',') != std::string::npos || o.to_text.find(',') != std::string::npos) {
    throw Error("--from/--to: give one composition each");
  }
  const auto model = o.source.Load(o.quiet);
  const auto [from, to] = CompositionRange(*model, o.from_text, o.to_text, o.source.extrapolate);

  // The model is named by its file or data set (the library's message names the method).
  const std::string source = o.source.model_path.empty() ? o.source.data_dir : o.source.model_path;
  std::unique_ptr<color::ColorSweep> made;
  try {
    made = std::make_unique<color::ColorSweep>(colorimeter, *model, o.angle_deg);
  } catch (const Error& e) {
    throw Error(source + ": " + e.what());
  }
  color::ColorSweep& sweep = *made;
  if (o.sigma && !model->HasUncertainty()) throw Error("--sigma: " + model->NoErrorBarReason());
  ThreadBudget threads(0);
  // The one-sigma of a block of rows at a time, computed across the threads.
  constexpr long long kSigmaBlock = 4096;
  std::vector<double> sigma_block;
  long long sigma_first = -1;
  // Sweeps of 1000 steps or more interpolate a table of XYZ (unless --exact).
  const bool table = sweep.BuildTableFor(static_cast<std::size_t>(o.steps), from, to, o.exact);
  const color::XYZ white = colorimeter.White();
  const bool json = o.format == "json";

  StreamOutput stream(o.out, &ProgramGuard());
  Output out(&stream);
  WriteHead(out, o, *model, colorimeter.illuminant(), table ? &sweep : nullptr);
  const double span = to - from;
  const double last = static_cast<double>(o.steps - 1);
  const long long tenth = o.steps >= kProgressMinSteps ? o.steps / 10 : 0;
  for (long long i = 0; i < o.steps; ++i) {
    if (tenth > 0 && i > 0 && i % tenth == 0 && i / tenth < 10) {
      Report(progress, "sweep: " + std::to_string(10 * (i / tenth)) + "% (" + std::to_string(i) +
                           " of " + std::to_string(o.steps) + " rows)");
    }
    const auto x_at = [&](long long row) {
      return row == 0 ? from : row == o.steps - 1 ? to : from + span * (row / last);
    };
    const double x = x_at(i);
    if (o.sigma && (sigma_first < 0 || i >= sigma_first + kSigmaBlock)) {
      sigma_first = i;
      sigma_block.assign(static_cast<size_t>(std::min(kSigmaBlock, o.steps - i)), 0.0);
      ParallelTasks(
          sigma_block.size(),
          [&](size_t k) {
            sigma_block[k] = color::DeltaE00Sigma(colorimeter, *model, x_at(i + k), o.angle_deg);
          },
          &threads);
    }
    const color::XYZ xyz = table ? sweep.XYZAt(x) : sweep.ExactXYZ(x);
    if (!std::isfinite(xyz.X) || !std::isfinite(xyz.Y) || !std::isfinite(xyz.Z)) {
      throw Error(source + ": composition x = " + Describe(x) + ": the " + model->method() +
                  " model gives no finite colour");
    }
    WriteRow(out, json, i == 0, x, xyz, white,
             o.sigma ? &sigma_block[static_cast<size_t>(i - sigma_first)] : nullptr);
    out.EndRow();
  }
  if (json) out.Text("\n]}\n");
  out.Flush();
  stream.Commit();
  if (!o.out.empty() && !o.quiet) {
    std::fprintf(stderr, "alloycolor: wrote %s\n", MessageLine(o.out).c_str());
  }
  if (table && !o.quiet) {
    std::fprintf(stderr,
                 "alloycolor: sweep: XYZ interpolated from a table of %d compositions, "
                 "measured error %.2g (at most %.0e; --exact evaluates each)\n",
                 sweep.table_nodes(), sweep.table_error(), color::kSweepTableTolerance);
  }
}

}  // namespace

void RegisterSweep(CLI::App& app) {
  auto o = std::make_shared<SweepOptions>();
  CLI::App* cmd = app.add_subcommand(
      "sweep", "Colour at evenly spaced compositions, one row each, as CSV or JSON");
  cmd->footer(
      "Colour of the alloy at --steps evenly spaced compositions from --from to --to (default: "
      "the model's range), one row each: x, XYZ (perfect reflector Y = 1), CIELAB (white = "
      "the illuminant's) and 8-bit sRGB, as CSV (x,X,Y,Z,L,a,b,srgb8_r,srgb8_g,srgb8_b) or "
      "JSON. Sweeps of 1000 steps or more read XYZ from a table of the model's colour "
      "against x (cubic interpolation between the training compositions), refined until the "
      "error measured at every table interval's midpoint is at most 1e-7 in X, Y and Z; "
      "--exact evaluates every composition instead. XYZ is printed to 7 decimals, Lab to "
      "4.");
  o->source.AddOptions(cmd, true);
  cmd->add_option("--from", o->from_text,
                  "First composition: 0.25, 25at%, 25wt% or 6k (default: the model's lowest)");
  cmd->add_option("--to", o->to_text, "Last composition (default: the model's highest)");
  cmd->add_option("--steps", o->steps,
                  "Number of compositions, 1 to 1e9 (a sweep past 1 GB needs --force)")
      ->capture_default_str();
  cmd->add_option("--angle", o->angle_deg, "Angle of incidence in degrees (0-90)")
      ->capture_default_str();
  cmd->add_option("--illuminant", o->illuminant, "CIE illuminant: A, C, D50, D65, E, F2, F11")
      ->capture_default_str();
  cmd->add_option("--observer", o->observer, "CIE observer: 2 (1931) or 10 (1964)")
      ->capture_default_str();
  cmd->add_option("--format", o->format, "csv or json")->capture_default_str();
  cmd->add_flag("--exact", o->exact, "Evaluate every composition exactly (no table)");
  cmd->add_flag("--sigma", o->sigma,
                "Add the column sigma_de00: the one-sigma CIEDE2000 at each composition, as "
                "`alloycolor color` gives it (64 draws a row, on every core: thousands of rows "
                "a second)");
  cmd->add_flag("--force", o->force,
                "Write a sweep past 1 GB (about 12.8 million CSV rows, 9 million JSON rows); "
                "without it such a sweep is refused before the work");
  cmd->add_option("--out", o->out,
                  "Write the rows to this file (streamed to a temporary beside it and renamed "
                  "when complete) instead of standard output (held, past 64 MiB in a "
                  "temporary file, until complete)");
  cmd->add_flag("--quiet", o->quiet, "No warnings or notes on stderr");
  cmd->callback([o]() { Run(*o); });
}

}  // namespace alloycolor::app
