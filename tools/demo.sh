#!/usr/bin/env bash
# The main job: the built-in sedan into a rigid wall at 56 km/h (scenes/wall_crash.json), rendered
# offscreen with the deformation heat map into out/wall_crash/ (video.mp4, summary.json, timeline.csv),
# plus the mesh report of the built-in car (out/demo/mesh_report.json) as an extra.
set -euo pipefail
build_dir=${1:-build}
sandbox="$build_dir/bin/sandbox"
start=$(date +%s)
"$sandbox" run wall_crash --out out/wall_crash --video --heatmap
mkdir -p out/demo
"$sandbox" mesh info builtin:sedan --control-points 60 --json > out/demo/mesh_report.json.tmp
mv out/demo/mesh_report.json.tmp out/demo/mesh_report.json
echo "demo: mesh report of the built-in sedan in out/demo/mesh_report.json"
echo "demo: video of the wall crash in out/wall_crash/video.mp4 (figures in out/wall_crash/summary.json;" \
  "$(($(date +%s) - start)) s)"
