#!/usr/bin/env bash
# Benchmarks, each figure beside the straightforward implementation measured in the same
# run: colours per second through each model (bench/colour_bench.cc), matches per second
# (bench/match_bench.cc) and 100,000 targets matched from Python, rendering 1024 x 1024
# tiles (bench/render_bench.cc), the end-to-end `alloycolor sweep` of a million
# compositions, smooth-fit time against data size (bench/fit_bench.cc), exact colours from
# Python, `fit` and `validate --loo` of Au-Ag on one core and two, fits and validation of a
# composition-spread library of 50-1000 samples (bench/spread_bench.cc), and the wall time
# of `alloycolor validate --loo --methods all` on every bundled data set. The machine's load
# stands beside each figure. Builds build/
# (Release) first. Prints the machine, its load, and the figures with ratios to the
# straightforward implementation ("naive") or the issue's target where there is none.
#   scripts/bench.sh [--quick]      (--quick: shorter runs, less stable figures, no direct
#                                    rendering, each validation stopped after 5 s instead of
#                                    20 s and not repeated without auto)
# BUILD_DIR=dir uses an existing Release build there instead of setting up build/.
set -euo pipefail
cd "$(dirname "$0")/.."
# What it prints also becomes docs/performance.md (a header naming the command, date,
# commit and machine, then the output), once the run has succeeded.
if [[ -z ${ALLOYCOLOR_BENCH_INNER:-} ]]; then
  log=$(mktemp)
  status=0
  ALLOYCOLOR_BENCH_INNER=1 bash "$0" "$@" | tee "$log" || status=$?
  if [[ $status == 0 ]]; then
    {
      echo "# Performance"
      echo
      echo "Written by \`scripts/bench.sh $*\` on $(date -u +%F), commit" \
           "$(git rev-parse --short HEAD 2>/dev/null || echo unknown). Every figure stands beside a" \
           "straightforward implementation measured in the same run (\"naive\"), or the target."
      echo
      echo '```'
      cat "$log"
      echo '```'
    } > docs/performance.md.tmp && mv docs/performance.md.tmp docs/performance.md
    echo "bench: wrote docs/performance.md" >&2
  fi
  rm -f "$log"
  exit "$status"
fi
min_time=1.0
sweep_runs=3
fit_repetitions=5
fit_min_time=0.5
exact_steps=1000000
validate_limit=20
quick=0
if [[ ${1:-} == --quick ]]; then
  quick=1
  min_time=0.2
  sweep_runs=1
  fit_repetitions=2
  fit_min_time=0.05
  exact_steps=200000
  validate_limit=5
fi
started=$EPOCHREALTIME
if [[ -z ${BUILD_DIR:-} ]]; then
  scripts/setup.sh >/dev/null
  BUILD_DIR=build
fi
out=$(mktemp -d)
part=0
trap 'rm -rf "$out"' EXIT
# The machine's load (its 1-minute average over the cores), printed beside each figure:
# figures are CPU-bound on shared cores, so a high load slows wall times.
load() { awk '{ printf "load %.2f", $1 }' /proc/loadavg; }

echo "== machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//'), $(awk '/MemTotal/ { printf "%.0f GB", $2 / 1048576 }' /proc/meminfo)"
echo "== load at the start: $(uptime | sed 's/.*load average/load average/') (other work shares the cores)"

echo "== colours per second (Au-Ag, D65, 2-degree observer, 5 nm grid; one core; $(load))"
# One run per set of counters (the CSV reporter wants the same counters on every row).
for filter in 'BM_(Naive|Library|SweepExact)/' 'BM_SweepTable/' 'BM_SweepTableBuild/'; do
  part=$((part + 1))
  "$BUILD_DIR"/bench/colour_bench --benchmark_min_time="$min_time" --benchmark_format=csv \
    --benchmark_filter="$filter" >"$out/colour-$part.csv" 2>/dev/null
done
awk -F, '
  function model(m) { split("paper eps-linear smooth eps-pchip eps-spline physical", names, " "); return names[m + 1] }
  FNR == 1 { delete col; for (i = 1; i <= NF; ++i) { h = $i; gsub(/"/, "", h); col[h] = i }; next }
  {
    name = $1; gsub(/"/, "", name)
    split(name, part, "/")
    kind = part[1]; sub(/^BM_/, "", kind)
    m = part[2]; sub(/model:/, "", m)
    angle = 0
    if (part[3] ~ /^angle:/) { angle = part[3]; sub(/angle:/, "", angle) }
    if (kind == "SweepTableBuild") {
      build[m] = $col["real_time"]; next
    }
    key = model(m) (angle != 0 ? " at " angle " deg" : "")
    rate[kind, key] = $col["items_per_second"]
    if (!(key in seen)) { seen[key] = 1; keys[++n] = key }
    if (kind == "SweepTable" && ("table_nodes" in col)) {
      nodes[key] = $col["table_nodes"]; err[key] = $col["table_error"]
    }
  }
  END {
    printf "%-20s %14s %14s %20s %20s\n", "model", "naive", "library", "sweep exact", "sweep table"
    for (i = 1; i <= n; ++i) {
      k = keys[i]; base = rate["Naive", k]
      printf "%-20s", k
      if (base > 0) printf " %12.3g/s", base; else printf " %14s", "-"
      if (rate["Library", k] != "") printf " %12.3g/s", rate["Library", k]; else printf " %14s", "-"
      printf " %12.3g/s", rate["SweepExact", k]
      if (base > 0) printf " (%4.1fx)", rate["SweepExact", k] / base; else printf " %7s", ""
      printf " %12.3g/s", rate["SweepTable", k]
      if (base > 0) printf " (%5.0fx)", rate["SweepTable", k] / base
      printf "\n"
    }
    printf "(ratios to naive; the table: "
    sep = ""
    for (i = 1; i <= n; ++i) if (nodes[keys[i]] != "") {
      printf "%s%s %d nodes, max error %.1e", sep, keys[i], nodes[keys[i]], err[keys[i]]; sep = "; "
    }
    printf "; built in"
    for (m = 0; m < 6; ++m) printf " %s %.1f ms", model(m), build[m]
    printf ")\n"
  }' "$out"/colour-*.csv

echo "== from colour to composition (Au-Ag smooth, D65, normal incidence; one core): matches per second ($(load))"
"$BUILD_DIR"/bench/match_bench --benchmark_min_time="$min_time" --benchmark_format=csv \
  >"$out/match.csv" 2>/dev/null
awk -F, '
  FNR == 1 { for (i = 1; i <= NF; ++i) { h = $i; gsub(/"/, "", h); col[h] = i }; next }
  { name = $1; gsub(/"/, "", name); rate[name] = $col["items_per_second"]; order[++n] = name }
  END {
    base = rate["BM_BruteForce"]
    for (i = 1; i <= n; ++i) {
      printf "  %-22s %10.4g /s  (%.3g ms each; %.3gx brute force)\n", order[i], rate[order[i]],
             1000 / rate[order[i]], rate[order[i]] / base
    }
  }' "$out/match.csv"

echo "== from colour to composition from Python: 100,000 targets in one model.match(labs, sigma=False) (all cores; best of 3; $(load))"
PYTHONPATH="$BUILD_DIR/python" /usr/bin/python3 - <<'PY'
import time
import numpy as np
import alloycolor as ac

# Targets: the model's colour at random compositions, moved by N(0, 0.5) in L*, a*, b*.
for name, method in (("Au-Ag", "smooth"), ("Cu-Zn/dataset-werner-zn.json", "eps-linear")):
    model = ac.Dataset(name).fit(method)
    rng = np.random.default_rng(1)
    lab = model.color(rng.uniform(0, 1, 100000))["lab"] + rng.normal(0, 0.5, (100000, 3))
    best = 1e300
    for _ in range(3):
        start = time.perf_counter()
        model.match(lab, sigma=False)
        best = min(best, time.perf_counter() - start)
    print("  %-30s %-10s %.2f s (%.1f us per target)" % (name, method, best, best * 10))
PY

echo "== rendering a 1024 x 1024 tile of gold (D65, transparent background): Mpixel/s of wall time ($(load))"
render_filter='BM_(Table|First|Reference|Direct)/'
[[ $quick == 0 ]] || render_filter='BM_(Table|First|Reference)/'
"$BUILD_DIR"/bench/render_bench --benchmark_min_time="$min_time" --benchmark_format=csv \
  --benchmark_filter="$render_filter" >"$out/render.csv" 2>/dev/null
awk -F, -v threads="$(nproc)" '
  FNR == 1 { for (i = 1; i <= NF; ++i) { h = $i; gsub(/"/, "", h); col[h] = i }; next }
  {
    name = $1; gsub(/"/, "", name)
    split(name, part, "/")
    kind = part[1]; sub(/^BM_/, "", kind)
    rate[kind, part[2], part[3]] = $col["Mpixel/s"]
    # Mpixel per second of processor time of the main thread (one thread: per core).
    cpu[kind, part[2], part[3]] = 1.048576 * 1000 / $col["cpu_time"]
  }
  function f(v) { return v == "" ? "-" : sprintf("%.3g", v) }
  END {
    scene[0] = "sphere, uniform light"; scene[1] = "sphere, studio light"; scene[2] = "ring, studio light"
    printf "%-22s %18s %10s %14s %16s %14s %11s\n", "scene", "per image: 1 core", "(cpu)", threads " threads", "first image 1/" threads, "straightforw.", "direct " threads
    for (s = 0; s < 3; ++s) {
      printf "%-22s %10s (%4.0fx) %10s %14s %16s %14s %11s\n", scene[s], f(rate["Table", s, 1]),
        rate["Table", s, 1] / rate["Reference", s, 1], f(cpu["Table", s, 1]), f(rate["Table", s, threads]),
        f(rate["First", s, 1]) " / " f(rate["First", s, threads]), f(rate["Reference", s, 1]),
        f(rate["Direct", s, threads])
    }
    printf "(per image: Renderer::Render with the tile traced when the Renderer was made; first image: the\n"
    printf " Renderer made as well; (cpu): per second of processor time; straightforward: every pixel traced, lit\n"
    printf " and coloured on its own, one thread (tests/reference_renderer.h), ratios to it; direct: spectral\n"
    printf " Fresnel at every sample. Sphere / ring, studio light, one core: per image %.2f, first image %.2f)\n",
      rate["Table", 1, 1] / rate["Table", 2, 1], rate["First", 1, 1] / rate["First", 2, 1]
  }' "$out/render.csv"

echo "== alloycolor sweep end to end: 1,000,000 compositions written to /dev/null (best of $sweep_runs; $(load))"
ac=$BUILD_DIR/app/alloycolor
$ac fit --data Au-Ag --method smooth --quiet --out "$out/smooth.json"
sweep_time() {
  local best="" start end
  for ((run = 0; run < sweep_runs; ++run)); do
    start=$EPOCHREALTIME
    "$ac" sweep --quiet "$@" >/dev/null
    end=$EPOCHREALTIME
    best=$(awk -v a="$best" -v s="$start" -v e="$end" \
      'BEGIN { b = e - s; print (a == "" || b < a + 0) ? b : a }')
  done
  echo "$best"
}
for spec in "smooth:--model $out/smooth.json" "paper:--data Au-Ag --method paper" \
            "eps-linear:--data Au-Ag --method eps-linear"; do
  name=${spec%%:*}
  # shellcheck disable=SC2086
  csv=$(sweep_time ${spec#*:} --steps 1000000)
  # shellcheck disable=SC2086
  json=$(sweep_time ${spec#*:} --steps 1000000 --format json)
  printf '%-11s csv %6.2f s   json %6.2f s\n' "$name" "$csv" "$json"
done
# --exact evaluates every composition: exact_steps of them, less a run of 2 (start-up).
exact=$(sweep_time --model "$out/smooth.json" --steps "$exact_steps" --exact)
startup=$(sweep_time --model "$out/smooth.json" --steps 2 --exact)
awk -v t="$exact" -v t0="$startup" -v n="$exact_steps" 'BEGIN {
  printf "%-11s csv %6.2f s   (--exact: every composition evaluated; %d timed, %.3g/s beyond start-up)\n", "smooth", (t - t0) * 1e6 / (n - 2) + t0, n, (n - 2) / (t - t0)
}'

echo "== fit time against data size (smooth, smoothing fixed; median of $fit_repetitions; $(load))"
"$BUILD_DIR"/bench/fit_bench --benchmark_format=csv --benchmark_repetitions="$fit_repetitions" \
  --benchmark_min_time="$fit_min_time" \
  2>/dev/null | awk -F, '
  NR == 1 { for (i = 1; i <= NF; ++i) { h = $i; gsub(/"/, "", h); col[h] = i }; next }
  $1 ~ /_median"?$/ {
    name = $1; gsub(/"/, "", name); sub(/_median$/, "", name); sub(/^BM_/, "", name)
    t = $col["real_time"]; it = ("ceres_iterations" in col) ? $col["ceres_iterations"] : ""
    split(name, part, "/")
    if (part[1] == "FitWavelengths") { sub(/x:/, "", part[2]); w[part[2]] = t; wi[part[2]] = it }
    else if (part[1] == "FitSamples") { sub(/samples:/, "", part[2]); s[part[2]] = t; si[part[2]] = it }
    else if (part[1] == "BuildModel") { sub(/method:/, "", part[2]); b[part[2]] = t }
    else d = t
  }
  END {
    printf "%-24s %12s %18s %18s\n", "", "1x", "2x", "4x (samples: 3.7x)"
    printf "%-24s %9.2f ms %9.2f ms (%.1fx) %9.2f ms (%.1fx)\n", "wavelengths 95/189/377", w[1], w[2], w[2] / w[1], w[4], w[4] / w[1]
    printf "%-24s %9.2f ms %9.2f ms (%.1fx) %9.2f ms (%.1fx)\n", "samples 3/6/11", s[3], s[6], s[6] / s[3], s[11], s[11] / s[3]
    printf "(the knots are the samples: one direct solve per wavelength, no Ceres iterations)\n"
    printf "smooth fit, smoothing cross-validated (11 samples, 95 nodes): %.1f ms\n", d
    printf "fit as alloycolor fit runs it, with its prediction error from 9 leave-one-out folds and 4 pair folds (wall time):\n"
    printf "  smooth %.0f ms (target 100 ms: %.2fx), physical %.0f ms, auto (every method scored, the best kept) %.0f ms\n", b[0], b[0] / 100, b[1], b[2]
  }'

echo "== exact colours from Python: 100,000 compositions of the Au-Ag default model (auto: physical) in one alloycolor.color(model, x, exact=True), against the straightforward loop in Python (best of 3)"
PYTHONPATH="$BUILD_DIR/python" /usr/bin/python3 - <<'PY'
import os, time
import numpy as np
import alloycolor as ac

def load():
    return "load %.2f" % os.getloadavg()[0]

model = ac.fit(ac.Dataset("Au-Ag"))
xs = np.random.default_rng(1).uniform(0.0, 1.0, 100000)
best = 1e300
for _ in range(3):
    start = time.perf_counter()
    ac.color(model, xs, exact=True)
    best = min(best, time.perf_counter() - start)
# The straightforward loop: one composition at a time through Model.color's single value.
few = xs[:2000]
start = time.perf_counter()
for x in few:
    ac.color(model, float(x), exact=True)
loop = (time.perf_counter() - start) * len(xs) / len(few)
print("  %s: %.3f s (%.2f us per composition; %s); one composition per call: %.2f s (%.0fx; %s; target 0.15 s)"
      % (model.method, best, best * 10, load(), loop, loop / best, load()))
PY

echo "== fit and leave-one-out validation of Au-Ag as the program runs them (wall time, best of 2): one core (taskset -c 0) and two"
best_of_2() {
  local best="" start end
  for ((run = 0; run < 2; ++run)); do
    start=$EPOCHREALTIME
    "$@" >/dev/null 2>&1
    end=$EPOCHREALTIME
    best=$(awk -v a="$best" -v s="$start" -v e="$end" \
      'BEGIN { b = e - s; print (a == "" || b < a + 0) ? b : a }')
  done
  echo "$best"
}
for cores in 0 0,1; do
  fit_auto=$(best_of_2 taskset -c "$cores" "$ac" fit --data Au-Ag --quiet --out "$out/auto.json")
  fit_load=$(load)
  loo=$(best_of_2 taskset -c "$cores" "$ac" validate --data Au-Ag --loo --methods all --quiet \
    --out "$out/validate-au-ag")
  printf '  cores %-4s fit (auto) %6.2f s (target 0.5 s; %s)   validate --loo --methods all %6.2f s (target 3 s; %s)\n' \
    "$cores" "$fit_auto" "$fit_load" "$loo" "$(load)"
done

echo "== a composition-spread library (bench/spread_bench.cc: Au-Ag from the physical model of Rioux's series, 1 % scatter per sample): library time against the samples (side by side: one run of each fit, the median of three validations)"
spread_filter='.'
[[ $quick == 0 ]] || spread_filter='BM_(Fit/method:0|Fit/method:[12]/samples:100|ValidateLoo)'
"$BUILD_DIR"/bench/spread_bench --benchmark_format=csv --benchmark_filter="$spread_filter" \
  >"$out/spread.csv" 2>/dev/null
awk -F, -v load="$(load)" '
  NR == 1 { for (i = 1; i <= NF; ++i) { h = $i; gsub(/"/, "", h); col[h] = i }; next }
  {
    name = $1; gsub(/"/, "", name); split(name, part, "/")
    kind = part[1]; sub(/^BM_/, "", kind)
    label = $col["label"]; gsub(/"/, "", label)
    t = $col["real_time"] / 1000
    if (kind == "Fit") { m = part[2]; sub(/method:/, "", m); n = part[3]; sub(/samples:/, "", n)
      fit[label, n] = t; if (!(label in seen)) { seen[label] = 1; order[++k] = label } }
    else if (name ~ /_median$/) { n = part[2]; sub(/samples:/, "", n); loo[n] = t }
  }
  function cell(m, n) { return (m, n) in fit ? sprintf("%8.2f s", fit[m, n]) : sprintf("%10s", "-") }
  END {
    printf "  %-12s %10s %10s %10s %10s   (fit as `alloycolor fit --method M` builds it; %s)\n", "samples", "50", "100", "300", "1000", load
    for (i = 1; i <= k; ++i) {
      m = order[i]
      printf "  %-12s %s %s %s %s", m, cell(m, 50), cell(m, 100), cell(m, 300), cell(m, 1000)
      if ((m, 100) in fit && (m, 1000) in fit) printf "   100 -> 1000: %.1fx", fit[m, 1000] / fit[m, 100]
      else if ((m, 100) in fit && (m, 300) in fit) printf "   100 -> 300: %.1fx", fit[m, 300] / fit[m, 100]
      printf "\n"
    }
    printf "  validate --loo --methods eps-linear: 50 samples %.2f s, 100 samples %.2f s (%.2fx for twice the samples; targets 2 s and 2.5x)\n", loo[50], loo[100], loo[100] / loo[50]
  }' "$out/spread.csv"
"$BUILD_DIR"/bench/spread_bench --write "$out/spread1000" 1000 >/dev/null
start=$EPOCHREALTIME
"$ac" fit --data "$out/spread1000" --method eps-linear --quiet --out "$out/spread1000.json"
awk -v s="$start" -v e="$EPOCHREALTIME" -v load="$(load)" 'BEGIN {
  printf "  alloycolor fit --method eps-linear, 1000 samples (reading their files and writing the model too): %.2f s (target 1 s; %s)\n", e - s, load }'

echo "== leave-one-out validation with every method (alloycolor validate --loo; one run each; stopped after ${validate_limit} s; $(load))"
# Wall time of one validation, or "> limit" when it was stopped.
validate_time() {
  local start end status=0
  start=$EPOCHREALTIME
  timeout "$validate_limit" "$ac" validate --loo --quiet --out "$out/validate" "$@" \
    >/dev/null 2>&1 || status=$?
  end=$EPOCHREALTIME
  awk -v s="$start" -v e="$end" -v st="$status" -v limit="$validate_limit" 'BEGIN {
    if (st == 124) printf "> %d s", limit
    else if (st != 0) printf "failed (%d)", st
    else printf "%.2f s", e - s
  }'
}
printf '%-34s %18s %28s   %s\n' "data set" "--methods all" "every method but auto" "(target 5 s)"
for manifest in data/Au-Ag/dataset.json data/Cu-Zn/dataset.json data/Cu-Zn/dataset-werner-zn.json \
                data/Nb-Sn/dataset.json; do
  [[ -f $manifest ]] || continue
  all=$(validate_time --data "$manifest" --methods all)
  rest=-
  if [[ $quick == 0 ]]; then
    rest=$(validate_time --data "$manifest" --methods paper,eps-linear,eps-pchip,eps-spline,smooth,physical)
  fi
  printf '%-34s %18s %28s\n' "$manifest" "$all" "$rest"
done
echo "== load at the end: $(uptime | sed 's/.*load average/load average/'); bench.sh took $(awk -v s="$started" -v e="$EPOCHREALTIME" 'BEGIN { printf "%.0f", e - s }') s"
