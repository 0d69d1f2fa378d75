#!/usr/bin/env bash
# Installs the Debian packages the project needs. Non-interactive and idempotent:
# when everything is present it only runs dpkg-query and exits.
set -euo pipefail

packages=(
  cmake g++ make pkg-config clang-format
  libode-dev        # rigid bodies (vehicle/)
  libccd-dev        # convex penetration queries (vehicle/, through ODE and directly)
  libeigen3-dev     # small dense linear algebra
  libassimp-dev     # mesh import and export
  libqhull-dev      # convex hulls (deform/)
  libmeshoptimizer-dev # hull simplification (deform/)
  libosmesa6-dev    # offscreen OpenGL (sandbox/)
  libpng-dev        # PNG frames
  nlohmann-json3-dev # scene files, --json output
  libcli11-dev      # command line
  catch2            # tests (v2)
  libbenchmark-dev  # Google Benchmark
  ffmpeg            # MP4 encoding, ffprobe in tests
  libbullet-dev     # Bullet's soft body: the baseline of bench grid
  gnuplot-nox       # plots of bench grid and tradeoff
  parallel          # GNU parallel: sweep shards on this machine or over ssh (tools/sweep/parallel.sh)
  munge slurmctld slurmd slurm-client # a one-node Slurm for the cluster test (tools/sweep/local-slurm.sh)
  clang             # libFuzzer and its sanitizer build (make fuzz; make test-asan is gcc's)
  libclang-rt-14-dev # clang's sanitizer and libFuzzer runtimes
  libomp-14-dev     # OpenMP for clang's build (GCC brings libgomp): cars stepped in parallel (vehicle/)
  llvm              # llvm-symbolizer: sanitizer reports with file and line
  pybind11-dev      # the Python module deform_sandbox (python/)
  python3-dev       # its headers, for Debian's /usr/bin/python3
  python3-numpy     # arrays of the module
  python3-pytest    # the module's tests (tests/python/)
  python3-matplotlib # examples/python/crush_sweep.py
)

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done

if [[ ${#missing[@]} -eq 0 ]]; then
  exit 0
fi

echo "setup: installing ${missing[*]}"
sudo_cmd=()
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "setup: not root and no sudo; install: ${missing[*]}" >&2; exit 1; }
  sudo_cmd=(sudo)
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "setup: done"
