# What every bench script checks before it runs, sourced by them (bash). Each check exits with a
# message naming what is missing.
# Sourced first (source "$(dirname "$0")/common.sh"): strict mode, `here` (the bench folder) and
# `threads` (THREADS, default 0 = all cores) for every script.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
threads="${THREADS:-0}"

require_jawmesh() {  # <path>
  [ -x "$1" ] || { echo "no jawmesh executable at $1 (build it, or pass its path)" >&2; exit 1; }
}
require_folder() {  # <path> <what it should hold>
  [ -d "$1" ] || { echo "no $2 at $1" >&2; exit 1; }
}
# The shared mandible case (JAWMESH_DATA, else ../shared/data beside the checkout), required; sets
# the variable named $1 (like make_work_dir).
require_mandible_case() {  # <variable name>
  local dir="${JAWMESH_DATA:-$here/../../shared/data}/openmandible"
  require_folder "$dir/input" "shared data"
  printf -v "$1" '%s' "$dir"
}
require_runs() {  # <count>
  [ "$1" -ge 1 ] || { echo "runs must be >= 1" >&2; exit 1; }
}
require_python3() {
  command -v python3 >/dev/null || { echo "python3 is needed to read the --json output" >&2; exit 1; }
}
require_time() {
  [ -x /usr/bin/time ] || { echo "/usr/bin/time (Debian package time) is needed for peak memory" >&2; exit 1; }
}
# A temporary folder, removed when the script exits: work_dir=$(make_work_dir) does not work (the
# trap would belong to the subshell), so it sets the variable named $1.
make_work_dir() {  # <variable name>
  local dir
  dir="$(mktemp -d)"
  printf -v "$1" '%s' "$dir"
  trap "rm -rf '$dir'" EXIT
}
# A work folder (make_work_dir) holding an empty results.jsonl, one JSON line per run; sets the
# variables named $1 (the folder) and $2 (the file).
make_results_file() {  # <folder variable> <file variable>
  make_work_dir "$1"
  printf -v "$2" '%s' "${!1}/results.jsonl"
  : > "${!2}"
}
