# Sourced by parallel.sh and submit.sh: reads "PLAN N [--runs DIR] [--result DIR] [other options...]" into
# plan and shards (absolute plan path), runs and result (absolute; default PLAN without .jsonl plus .runs
# and .result) and the array passed_options (everything else, for the scheduler). Exits 2 on bad input.
read_plan_args() {
  local usage_options=$1
  shift
  if [[ $# -lt 2 || ! $2 =~ ^[1-9][0-9]*$ ]]; then
    echo "usage: $0 PLAN N [--runs DIR] [--result DIR] [$usage_options...]" >&2
    exit 2
  fi
  plan=$(realpath "$1")
  shards=$2
  shift 2
  [[ -f $plan ]] || { echo "$0: $plan: no such plan" >&2; exit 2; }
  runs=${plan%.jsonl}.runs
  result=${plan%.jsonl}.result
  passed_options=()
  while [[ $# -gt 0 ]]; do
    case $1 in
      --runs) runs=$(realpath -m "$2"); shift 2 ;;
      --result) result=$(realpath -m "$2"); shift 2 ;;
      *) passed_options+=("$1"); shift ;;
    esac
  done
}
