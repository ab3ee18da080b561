#!/usr/bin/env bash
# The main job on the bundled data: set up, build, then the Au-Ag series as in the paper.
# Outputs go to out/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
ac=build/app/alloycolor
mkdir -p out

echo "== Colours of the Au-Ag series at the paper's compositions (paper baseline; D65, 2 deg, normal incidence)"
cat > out/paper-samples.json <<JSON
{"name": "Au-Ag at the paper's known compositions", "system": {"a": "Au", "b": "Ag"},
 "composition": "atomic_fraction_a",
 "samples": [{"x": 0.0, "file": "$PWD/data/Au-Ag/Rioux-Au0Ag100.yml"},
             {"x": 0.2, "file": "$PWD/data/Au-Ag/Rioux-Au20Ag80.yml"},
             {"x": 0.5, "file": "$PWD/data/Au-Ag/Rioux-Au50Ag50.yml"},
             {"x": 0.6, "file": "$PWD/data/Au-Ag/Rioux-Au60Ag40.yml"},
             {"x": 0.8, "file": "$PWD/data/Au-Ag/Rioux-Au80Ag20.yml"},
             {"x": 1.0, "file": "$PWD/data/Au-Ag/Rioux-Au100Ag0.yml"}]}
JSON
$ac color --data out/paper-samples.json --method paper --x 0,0.2,0.5,0.55,0.6,0.75,0.8,1 --quiet

echo "== Smooth Ceres fit to the paper's known compositions -> out/au-ag-smooth.json"
$ac fit --data out/paper-samples.json --method smooth --out out/au-ag-smooth.json
echo "== Predicted colours of Au 75 % and 55 % (atomic) and 18k, 14k (smooth model)"
$ac color --model out/au-ag-smooth.json --x 0.75,0.55,18k,14k

echo "== Smooth fit to all 11 Au-Ag samples -> out/au-ag-all.json"
$ac fit --data Au-Ag --out out/au-ag-all.json --quiet
$ac color --model out/au-ag-all.json --x 0,0.25,0.5,0.75,1 --quiet
