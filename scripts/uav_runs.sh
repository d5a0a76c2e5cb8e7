#!/bin/sh
# The runs behind docs/studies/drone-delivery.md: the reference trial, one-week checks, a
# reduced grid (CPU was scarce: see the page) and the forecasting comparison; then the figures.
# Usage: scripts/uav_runs.sh [swarmvm] [results folder] [workers]. Resumable: rerun to finish.
set -e
S=${1:-swarmvm}
OUT=${2:-build/uav-sweep}
W=${3:-2}
mkdir -p "$OUT"
$S sim uav --json > "$OUT/reference-8weeks.json"
$S sim uav --json --weeks 1 > "$OUT/reference-1week.json"
$S sim uav --json --weeks 1 --rule threshold --threshold 0.8 > "$OUT/reference-1week-threshold80.json"
$S sweep uav -o "$OUT" --taus 20 --runs 20 --thresholds 0.8 --workers "$W" --no-progress
$S sweep uav -o "$OUT" --taus 5,10,15,25,30,35,40 --runs 5 --thresholds 0.8 --workers "$W" --no-progress
$S sweep uav -o "$OUT" --taus 20 --runs 5 --rules '' --thresholds 0.5,0.6,0.7,0.9,1.0 --workers "$W" --no-progress
$S sweep uav -o "$OUT" --taus 20 --runs 5 --rules least-confident --thresholds '' --pretrain-weeks 8 --workers "$W" --no-progress
$S sweep uav -o "$OUT" --taus 20 --runs 5 --rules least-confident --thresholds '' --pretrain-weeks 8 --forecast --workers "$W" --no-progress
$S plot uav "$OUT" -o docs/studies/img
