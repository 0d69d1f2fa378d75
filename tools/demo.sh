#!/usr/bin/env bash
# The main job on the built-in default car. Until the scene runner exists this is the mesh report.
set -euo pipefail
build_dir=${1:-build}
out=out/demo
mkdir -p "$out"
"$build_dir/bin/sandbox" mesh info builtin:sedan --control-points 60 --json > "$out/mesh_report.json.tmp"
mv "$out/mesh_report.json.tmp" "$out/mesh_report.json"
"$build_dir/bin/sandbox" mesh info builtin:sedan --control-points 60
echo "demo: report written to $out/mesh_report.json"
