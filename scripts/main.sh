#!/usr/bin/env bash
# The main job on the bundled data: set up, build, then the Au-Ag series as in the paper.
# Outputs go to out/.
set -euo pipefail
cd "$(dirname "$0")/.."
ALLOYCOLOR_TARGETS=alloycolor scripts/setup.sh
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

echo "== Pictures of Au 75 % and 55 % (atomic; then 75 and 55 wt%) from the smooth model -> out/*.png"
$ac render --model out/au-ag-smooth.json --x 0.75,0.55 --out out/au75-au55-sphere.png
$ac render --model out/au-ag-smooth.json --x 0.75,0.55 --shape ring --out out/au75-au55-ring.png
$ac render --model out/au-ag-smooth.json --x 75wt%,55wt% --out out/au75wt-au55wt-sphere.png

echo "== Validation on the paper's split: train on Au 0, 20, 50, 60, 80, 100 %, predict the rest -> out/report-paper-split/"
$ac validate --data Au-Ag --holdout 0.1,0.3,0.4,0.7,0.9 --methods paper,eps-linear,smooth,physical \
  --angles 0,45 --out out/report-paper-split

echo "== Fit to all 11 Au-Ag samples (method chosen by leave-one-out: auto) -> out/au-ag-all.json, and its composition chart"
$ac fit --data Au-Ag --out out/au-ag-all.json --quiet
$ac chart --model out/au-ag-all.json --from 0 --to 1 --steps 11 --out out/au-ag-chart.svg
$ac chart --model out/au-ag-all.json --from 0 --to 1 --steps 11 --out out/au-ag-chart.png
echo "Open out/report-paper-split/report.html in a browser for the full report."
