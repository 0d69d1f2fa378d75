#!/usr/bin/env bash
# The post grid of docs/STABILITY.md ("Measured"): the built-in sedan (1500 kg, crush coupling) into a
# post 6 m ahead, over post sizes, offsets from its centre line, speeds and physics rates, for each preset
# given. One CSV row a run: what it ran, sandbox run's exit code, the energy watch's largest created share,
# the highest the vehicle frame's origin rose, the largest deviation, tunnelled and diverged.
#   tools/post_grid.sh SANDBOX OUT.csv PRESET...        e.g. tools/post_grid.sh build/bin/sandbox grid.csv fast balanced
# The grid's axes can be set from the environment (each a space-separated list; POSTS of "radius height"
# pairs separated by commas): POSTS, OFFSETS, SPEEDS, RATES. The defaults are the grid of STABILITY.md's
# first table; its widened grid is
#   POSTS="0.03 0.3,0.03 3.0,0.1 1.0,0.3 0.3,0.5 1.0,0.5 3.0" SPEEDS="60 150 250" RATES="60 500 1000"
set -uo pipefail
sandbox=$1
out=$2
shift 2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
scene="$work/post.json"
cat > "$scene" <<'JSON'
{"duration_s": 2.0, "physics_hz": 500,
 "vehicle": {"mesh": "builtin:sedan?vertices=20000", "mass_kg": 1500, "coupling": "crush",
             "start": {"position_m": [0, 0], "speed_kmh": 100}},
 "obstacles": [{"type": "post", "position_m": [6, 0], "radius_m": 0.1, "height_m": 1.5}]}
JSON
echo "preset,radius_m,height_m,offset_m,speed_kmh,physics_hz,exit,created_share,highest_m,max_deviation_m,tunnelled,diverged" > "$out"
for preset in "$@"; do
  IFS=, read -ra posts <<<"${POSTS:-0.1 1.5,0.3 0.8,0.3 2.5,0.03 0.3,0.5 3.0,0.05 1.0}"
  for post in "${posts[@]}"; do
    read -r radius height <<<"$post"
    for offset in ${OFFSETS:-0 0.5 1.0}; do
      for speed in ${SPEEDS:-60 100 150 200 250}; do
        for hz in ${RATES:-120 500 1000}; do
          run="$work/run"
          rm -rf "$run"
          "$sandbox" run "$scene" --out "$run" --set "vehicle.deformation.preset=$preset" \
            --set "vehicle.start.speed_kmh=$speed" --set "physics_hz=$hz" --set "obstacles.0.radius_m=$radius" \
            --set "obstacles.0.height_m=$height" --set "obstacles.0.position_m=[6,$offset]" > /dev/null 2>&1
          code=$?
          row=$(python3 - "$run" <<'PY'
import csv, json, sys
run = sys.argv[1]
s = json.load(open(run + "/summary.json"))
highest = max(float(r["car0.z_m"]) for r in csv.DictReader(open(run + "/timeline.csv")))
c = s["cars"][0]
print(f'{s["energy_watch"]["largest_created_share"]:.4f},{highest:.3f},{c["max_deviation_m"]:.3f},'
      f'{str(c["tunnelled"]).lower()},{str(c["diverged"]).lower()}')
PY
          )
          echo "$preset,$radius,$height,$offset,$speed,$hz,$code,$row" >> "$out"
        done
      done
    done
  done
done
