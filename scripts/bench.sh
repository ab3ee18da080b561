#!/usr/bin/env bash
# Benchmarks: colours per second through each model (bench/colour_bench.cc), smooth-fit
# time against data size (bench/fit_bench.cc), and the end-to-end `alloycolor sweep` of a
# million compositions with its output. Builds build/ (Release) first. Prints the machine
# and the figures, with ratios to the straightforward implementation ("naive").
#   scripts/bench.sh [--quick]      (--quick: shorter runs, less stable figures)
set -euo pipefail
cd "$(dirname "$0")/.."
min_time=1.0
[[ ${1:-} == --quick ]] && min_time=0.2
scripts/setup.sh >/dev/null
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

echo "== machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')"

echo "== colours per second (Au-Ag, D65, 2-degree observer, 5 nm grid; one core)"
build/bench/colour_bench --benchmark_min_time="$min_time" --benchmark_format=csv \
  >"$out/colour.csv" 2>/dev/null
awk -F, '
  function model(m) { return m == 0 ? "paper" : m == 1 ? "eps-linear" : "smooth" }
  NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
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
    if (kind == "SweepTable" && col["table_nodes"]) {
      nodes[key] = $col["table_nodes"]; err[key] = $col["table_error"]
    }
  }
  END {
    printf "%-20s %14s %14s %20s %20s\n", "model", "naive", "library", "sweep exact", "sweep table"
    for (i = 1; i <= n; ++i) {
      k = keys[i]; base = rate["Naive", k]
      printf "%-20s", k
      printf " %12.3g/s", base
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
    for (m = 0; m < 3; ++m) printf " %s %.1f ms", model(m), build[m]
    printf ")\n"
  }' "$out/colour.csv"

echo "== alloycolor sweep end to end: 1,000,000 compositions written to /dev/null (best of 3)"
ac=build/app/alloycolor
$ac fit --data Au-Ag --quiet --no-covariance --out "$out/smooth.json"
sweep_time() {
  local best="" start end
  for _ in 1 2 3; do
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
# shellcheck disable=SC2086
printf '%-11s csv %6.2f s   (--exact: every composition evaluated)\n' "smooth" \
  "$(sweep_time --model "$out/smooth.json" --steps 1000000 --exact)"

echo "== smooth fit time against data size (median of 3)"
build/bench/fit_bench --benchmark_format=csv 2>/dev/null | awk -F, '
  NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
  $1 ~ /_median"?$/ {
    name = $1; gsub(/"/, "", name); sub(/_median$/, "", name); sub(/^BM_/, "", name)
    t = $col["real_time"] / 1000
    split(name, part, "/")
    if (part[1] == "FitWavelengths") { sub(/x:/, "", part[2]); w[part[2]] = t }
    else if (part[1] == "FitSamples") { sub(/samples:/, "", part[2]); s[part[2]] = t }
    else d = t
  }
  END {
    printf "wavelengths (11 samples, degree 2):  95 nodes %.2f s, 189 nodes %.2f s (%.1fx), 377 nodes %.2f s (%.1fx)\n", w[1], w[2], w[2] / w[1], w[4], w[4] / w[1]
    printf "samples (95 nodes, degree 2):        3 samples %.2f s, 6 samples %.2f s (%.1fx), 11 samples %.2f s (%.1fx)\n", s[3], s[6], s[6] / s[3], s[11], s[11] / s[3]
    printf "default fit (cross-validated degree, covariance; 11 samples, 95 nodes): %.2f s\n", d
  }'
