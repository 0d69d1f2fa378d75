#!/usr/bin/env bash
# tools/setup.sh [demo|test|ci] [--print]
#
# Installs the Debian packages one command needs, and no more: `demo` (make demo: the program and what
# it links), `test` (make build, make test: the tests, benchmarks, Bullet, Python, the sweeps' tools and a
# one-node Slurm), `ci` (everything: test's, plus clang and LLVM for make fuzz and make test-asan; also the
# default). Each list contains the one before it. --print prints the list, one package a line, and installs
# nothing. Non-interactive and idempotent: when everything is present it only runs dpkg-query and exits.
# Nothing installed is left running or enabled as a service (see below).
set -euo pipefail

command=ci
print=false
for arg in "$@"; do
  case $arg in
    demo | test | ci) command=$arg ;;
    --print) print=true ;;
    *) echo "usage: tools/setup.sh [demo|test|ci] [--print]" >&2; exit 2 ;;
  esac
done

demo_packages=(
  cmake g++ make pkg-config
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
  ffmpeg            # MP4 encoding, ffprobe in tests
)
test_packages=(
  clang-format      # make format
  catch2            # tests (v2)
  libbenchmark-dev  # Google Benchmark
  libbullet-dev     # Bullet's soft body: the baseline of bench grid
  gnuplot-nox       # plots of bench grid and tradeoff
  parallel          # GNU parallel: sweep shards on this machine or over ssh (tools/sweep/parallel.sh)
  munge slurmctld slurmd slurm-client # a one-node Slurm for the cluster test (tools/sweep/local-slurm.sh)
  pybind11-dev      # the Python module deform_sandbox (python/)
  python3-dev       # its headers, for Debian's /usr/bin/python3
  python3-numpy     # arrays of the module
  python3-pytest    # the module's tests (tests/python/)
  python3-matplotlib # examples/python/crush_sweep.py
)
ci_packages=(
  clang             # libFuzzer and its sanitizer build (make fuzz; make test-asan is gcc's)
  libclang-rt-14-dev # clang's sanitizer and libFuzzer runtimes
  libomp-14-dev     # OpenMP for clang's build (GCC brings libgomp): cars stepped in parallel (vehicle/)
  llvm              # llvm-symbolizer: sanitizer reports with file and line
)

packages=("${demo_packages[@]}")
[[ $command == demo ]] || packages+=("${test_packages[@]}")
[[ $command != ci ]] || packages+=("${ci_packages[@]}")

if $print; then
  printf '%s\n' "${packages[@]}"
  exit 0
fi

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done

if [[ ${#missing[@]} -eq 0 ]]; then
  exit 0
fi

echo "setup ($command): installing ${#missing[@]} packages and what they depend on: ${missing[*]}"
sudo_cmd=()
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "setup: not root and no sudo; install: ${missing[*]}" >&2; exit 1; }
  sudo_cmd=(sudo)
fi
export DEBIAN_FRONTEND=noninteractive
log=$(mktemp /tmp/deform-setup.XXXXXX.log)

# Debian starts a package's service on install (munge, slurmctld and slurmd among ours), and on a systemd
# machine enables it for every boot. The cluster test starts its own one-node Slurm and stops it again
# (tools/sweep/local-slurm.sh), so nothing here may be left running: a policy-rc.d that denies every start
# while apt runs (unless the machine has one already, as container images do), then every service of a
# package this run installed disabled.
policy=/usr/sbin/policy-rc.d
own_policy=false
if [[ ! -e $policy ]]; then
  printf '#!/bin/sh\n# tools/setup.sh: no service starts while it installs packages.\nexit 101\n' |
    "${sudo_cmd[@]}" tee "$policy" >/dev/null
  "${sudo_cmd[@]}" chmod 755 "$policy"
  own_policy=true
fi
cleanup() {
  if $own_policy; then "${sudo_cmd[@]}" rm -f "$policy"; fi
}
trap cleanup EXIT
trap 'exit 130' INT TERM

installed() { dpkg-query -W -f='${db:Status-Abbrev} ${Package}\n' | awk '$1 == "ii" {print $2}' | sort; }
before=$(installed)
start=$(date +%s)
echo "setup: apt-get update"
"${sudo_cmd[@]}" apt-get update -qq
# apt's summary (how many packages, how many MB to download) is shown as it starts; the rest goes to the
# log, shown on failure.
echo "setup: apt-get install (log: $log)"
set +o pipefail
"${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}" 2>&1 | tee "$log" |
  awk '/^[0-9]+ upgraded|^Need to get/ {print "setup: " $0; fflush()}'
status=${PIPESTATUS[0]}
set -o pipefail
if [[ $status -ne 0 ]]; then
  tail -20 "$log" >&2
  echo "setup: apt-get install failed (log: $log)" >&2
  exit 1
fi

# Every service unit and init script of a package this run was asked to install (munge, slurmctld, slurmd;
# not the dependencies apt brought with them, such as dbus, which the machine may need).
units=()
scripts=()
while read -r p; do
  while read -r f; do
    case $f in
      /lib/systemd/system/*.service | /lib/systemd/system/*.socket | /lib/systemd/system/*.timer | \
        /usr/lib/systemd/system/*.service | /usr/lib/systemd/system/*.socket | /usr/lib/systemd/system/*.timer)
        units+=("$(basename "$f")") ;;
      /etc/init.d/*) scripts+=("$(basename "$f")") ;;
    esac
  done < <(dpkg-query -L "$p" 2>/dev/null)
done < <(comm -12 <(comm -13 <(echo "$before") <(installed)) <(printf '%s\n' "${missing[@]}" | sort))
systemd_runs=false
[[ -d /run/systemd/system ]] && systemd_runs=true
for u in "${units[@]}"; do
  if $systemd_runs; then
    "${sudo_cmd[@]}" systemctl disable --now --quiet "$u" 2>/dev/null || true
  elif command -v systemctl >/dev/null; then
    "${sudo_cmd[@]}" systemctl disable --quiet "$u" 2>/dev/null || true  # the boot-time links only
  fi
done
for s in "${scripts[@]}"; do
  if ! $systemd_runs; then
    # No systemd: a policy-rc.d the machine already had may have let the script start it.
    "${sudo_cmd[@]}" "/etc/init.d/$s" stop >/dev/null 2>&1 || true
    "${sudo_cmd[@]}" update-rc.d "$s" disable >/dev/null 2>&1 || true
  fi
done
if [[ ${#units[@]} -gt 0 || ${#scripts[@]} -gt 0 ]]; then
  echo "setup: not running, disabled: $(printf '%s\n' "${units[@]}" "${scripts[@]}" | sed 's/\.service$//' | sort -u | xargs)"
fi
rm -f "$log"
echo "setup: done in $(($(date +%s) - start)) s"
