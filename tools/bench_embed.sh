#!/usr/bin/env bash
# Measures the embedding's deform pass (sandbox bench embed) over the cases in docs/BENCHMARKS.md and
# prints a Markdown table. Usage: tools/bench_embed.sh [build-dir]
set -euo pipefail
bin=${1:-build}/bin/sandbox
cases=(
  "--vertices 900000 --control-points 60 --k 8 --threads 1"
  "--vertices 900000 --control-points 60 --k 8 --threads 2"
  "--vertices 900000 --control-points 60 --k 4 --threads 2"
  "--vertices 900000 --control-points 60 --k 16 --threads 2"
  "--vertices 900000 --control-points 60 --k 0 --threads 2"
  "--vertices 4000000 --control-points 1000 --k 8 --threads 2"
)
echo "| vertices | N | K | threads | pass ms | B/vertex | GB/s | copy GB/s | of copy | AoS ms | speed-up | skin build ms |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
for c in "${cases[@]}"; do
  # shellcheck disable=SC2086
  "$bin" bench embed $c --repetitions 31 --json | python3 -c "$(cat <<'PY'
import json, sys
r = json.load(sys.stdin)
k = "dense" if r["k"] == r["control_points"] else r["k"]
cells = [f"{r['vertices']:,}", r["control_points"], k, r["threads"], f"{r['ms']:.2f}", r["bytes_per_vertex"],
         f"{r['gb_per_s']:.1f}", f"{r['copy_gb_per_s']:.1f}", f"{100 * r['bandwidth_fraction']:.0f} %",
         f"{r['baseline_aos_ms']:.2f}", f"{r['speedup_vs_aos']:.1f}x", f"{r['skin_build_ms']:.0f}"]
print("| " + " | ".join(str(c) for c in cells) + " |")
PY
)"
done
