#!/usr/bin/env bash
# Runs every libFuzzer target of a DEFORM_FUZZ build for SECONDS each (make fuzz; docs/GUIDE.md "CI jobs").
#   tools/fuzz.sh BUILD_DIR [SECONDS] [SEED]
# Corpus of each target, in BUILD_DIR/fuzz/<target>/: the seeds fuzz_seeds writes (small meshes in every
# format, the shipped scenes with and without --set overrides), the committed findings
# (tests/fuzz/regressions/<target>/), and, when DEFORM_TEST_MESHES is set, the shared meshes of the
# target's format under 256 KB (read in place, never copied into the repository). Fails on any crash,
# sanitizer report, leak, input that takes over 1 s of CPU time, or more than 2 GB of memory; the input is left in
# BUILD_DIR/fuzz/<target>/artifacts/ and must become a file in tests/fuzz/regressions/<target>/.
set -euo pipefail
build=${1:?usage: tools/fuzz.sh BUILD_DIR [SECONDS] [SEED]}
seconds=${2:-60}
# libFuzzer's seed: a fixed one makes a run from a fresh corpus reproducible (CI's); 0 lets libFuzzer
# pick one (a wider search over repeated runs).
seed=${3:-1}
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$(cd "$build" && pwd)"
bin="$build/bin"
work="$build/fuzz"
mkdir -p "$work"
"$bin/fuzz_seeds" "$work/seeds" >/dev/null

extensions_of() {  # target -> extensions of the shared meshes it takes
  case "$1" in
    mesh_stl) echo stl ;; mesh_obj) echo obj ;; mesh_ply) echo ply ;;
    mesh_gltf) echo gltf ;; mesh_glb) echo glb ;; *) echo "" ;;
  esac
}

failed=()
for target in scene mesh_obj mesh_stl mesh_ply mesh_gltf mesh_glb; do
  dir="$work/$target"
  rm -rf "$dir/artifacts"
  mkdir -p "$dir/corpus" "$dir/artifacts" "$dir/shared"
  inputs=("$work/seeds/$target" "$root/tests/fuzz/regressions/$target")
  shared=0
  if [[ -n "${DEFORM_TEST_MESHES:-}" && -d "${DEFORM_TEST_MESHES}" ]]; then
    for ext in $(extensions_of "$target"); do
      while IFS= read -r -d '' f; do
        ln -sf "$f" "$dir/shared/$(echo "$f" | md5sum | cut -c1-12).$ext"
        shared=$((shared + 1))
      done < <(find -L "$DEFORM_TEST_MESHES" -iname "*.$ext" -size -256k -print0)
    done
  fi
  [[ $shared -gt 0 ]] && inputs+=("$dir/shared")
  echo "fuzz: $target for ${seconds} s ($shared shared meshes among the seeds)"
  started=$(date +%s)
  # Over 1 s of CPU time per input is a finding (tests/fuzz/cpu_budget.hpp); -timeout=10 (wall clock)
  # catches one that never returns; -rss_limit_mb: over 2 GB is one too.
  # -malloc_limit_mb: libFuzzer's limit on one allocation (by default the RSS limit) is a hook that the
  # import's child process inherits; there assimp's allocation for a file that declares a billion
  # vertices wrote an "oom-" file from the child, for a file the parent then refused. The child has its
  # own CPU limit; this process keeps its 2 GB RSS limit.
  if "$bin/fuzz_$target" -max_total_time="$seconds" -seed="$seed" -timeout=10 -rss_limit_mb=2048 \
      -malloc_limit_mb=65536 -print_final_stats=1 \
      -artifact_prefix="$dir/artifacts/" "$dir/corpus" "${inputs[@]}" >"$dir/log.txt" 2>&1; then
    # A crash file left behind with a passing run is a finding all the same (a handler of libFuzzer's
    # that ran in a child process, say).
    if [[ -n "$(ls -A "$dir/artifacts")" ]]; then
      echo "fuzz: $target left inputs in $dir/artifacts/: $(ls "$dir/artifacts" | head -3)" >&2
      failed+=("$target")
      continue
    fi
    runs=$(awk '/stat::number_of_executed_units/ {print $2}' "$dir/log.txt")
    corpus=$(find "$dir/corpus" -type f | wc -l)
    echo "fuzz: $target passed: ${runs:-?} inputs run in $(( $(date +%s) - started )) s, corpus $corpus inputs"
  else
    echo "fuzz: $target FAILED; the end of $dir/log.txt:" >&2
    tail -n 40 "$dir/log.txt" >&2
    echo "fuzz: the input is in $dir/artifacts/; add it to tests/fuzz/regressions/$target/" >&2
    failed+=("$target")
  fi
done
if [[ ${#failed[@]} -gt 0 ]]; then
  echo "fuzz: findings in ${failed[*]}" >&2
  exit 1
fi
echo "fuzz: every target ran ${seconds} s with no finding"
