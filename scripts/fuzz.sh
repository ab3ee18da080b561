#!/usr/bin/env bash
# Builds the libFuzzer targets of fuzz/ with clang into build-fuzz/ and runs each for a
# bounded time, seeded from data/, tests/ and fuzz/seeds/; "page" is the explorer page's
# parsers under Node (fuzz/page_parser_fuzz.js: exceptions, ranges, linear work).
#   scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]
#   (default 60 s; yaml csv manifest model page)
# The growing corpus stays in build-fuzz/corpus/; inputs that crash go to
# build-fuzz/artifacts/ (copy them to tests/fuzz-regressions/TARGET/ once fixed; the
# fuzz_regressions test replays them). Exits 1 when any target found something.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true
targets=("$@")
((${#targets[@]})) || targets=(yaml csv manifest model page)
native=()
for t in "${targets[@]}"; do [[ $t == page ]] || native+=("$t"); done

# clang and its sanitizer/fuzzer runtime, from Debian, only what is missing.
missing=()
for p in clang libclang-rt-14-dev cmake ninja-build nodejs; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  scripts/setup.sh "${missing[@]}"
fi

CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DALLOYCOLOR_BUILD_FUZZERS=ON -DALLOYCOLOR_BUILD_TESTS=OFF -DALLOYCOLOR_BUILD_BENCH=OFF >/dev/null
((${#native[@]} == 0)) || cmake --build build-fuzz -j"${JOBS:-2}" --target "${native[@]/%/_fuzzer}"

# Seeds for each target: folders (read-only corpora) and files copied into a seed folder.
seed_dir() {
  local target=$1 dir=build-fuzz/seeds/$1
  rm -rf "$dir" && mkdir -p "$dir"
  shopt -s nullglob globstar
  local files=()
  case $target in
    yaml) files=(data/**/*.yml tests/bad-inputs/*.yml tests/bad-inputs/*.yaml
                 tests/fuzz-regressions/manifest-files/*.yml) ;;
    csv) files=(tests/bad-inputs/*.csv tests/fuzz-regressions/manifest-files/*.csv
                data/cie/illuminant-D65.csv) ;;
    manifest) files=(data/*/dataset*.json tests/bad-inputs/*.dataset.json fuzz/seeds/manifest/*) ;;
    model) files=(tests/bad-inputs/*.model.json fuzz/seeds/model/*) ;;
  esac
  local f
  for f in "${files[@]}" tests/fuzz-regressions/"$target"/*; do
    cp "$f" "$dir/$(echo "$f" | tr '/' '_')"
  done
  echo "$dir"
}

mkdir -p build-fuzz/artifacts
summary=()
found=0
for target in "${targets[@]}"; do
  if [[ $target == page ]]; then
    log=build-fuzz/page.log
    echo "== fuzzing page for ${seconds}s (log $log)"
    set +e
    node fuzz/page_parser_fuzz.js "$seconds" build-fuzz/artifacts >"$log" 2>&1
    status=$?
    set -e
    ((status == 0)) || { found=1; grep -m3 'FUZZ FINDING' "$log" || tail -3 "$log"; }
    summary+=("$(printf '%-9s %s' page "$(tail -1 "$log")")")
    continue
  fi
  corpus=build-fuzz/corpus/$target
  mkdir -p "$corpus"
  seeds=$(seed_dir "$target")
  dict=()
  [[ -f fuzz/$target.dict ]] && dict=(-dict="fuzz/$target.dict")
  log=build-fuzz/$target.log
  echo "== fuzzing $target for ${seconds}s (log $log)"
  before=$(ls build-fuzz/artifacts | wc -l)
  # -fork would use more cores; the machines here have two, and other work runs too.
  set +e
  build-fuzz/fuzz/"$target"_fuzzer "$corpus" "$seeds" "${dict[@]}" \
    -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=65536 \
    -artifact_prefix=build-fuzz/artifacts/"$target"- -print_final_stats=1 >"$log" 2>&1
  status=$?
  set -e
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo "?")
  units=$(ls "$corpus" | wc -l)
  new=$(($(ls build-fuzz/artifacts | wc -l) - before))
  if ((status != 0 || new > 0)); then
    found=1
    grep -m3 -E 'FUZZ FINDING|ERROR: (AddressSanitizer|libFuzzer)|runtime error|Test unit written' "$log" || true
  fi
  summary+=("$(printf '%-9s %10s executions  %6s corpus inputs  %s' "$target" "$execs" "$units" \
    "$( ((status != 0 || new > 0)) && echo "FOUND (status $status, see $log)" || echo "nothing found")")")
done
echo "== fuzzing summary (${seconds}s per target)"
printf '%s\n' "${summary[@]}"
exit "$found"
