#!/usr/bin/env bash
# Wall time of `superball derive --all` for two builds side by side
# (alternating, RUNS runs each), and whether their JSON is the same bytes
# (or holds every field of the old output unchanged, new fields added):
#
#   bench/derive_side_by_side.sh OLD_SUPERBALL NEW_SUPERBALL [RUNS]
#
# NEW_ARGS adds options to the new build's command only: a build whose JSON
# is compact (every build since the elimination forms) is compared with an
# older one as NEW_ARGS=--expanded.  ARGS adds options to both commands
# (ARGS="-j 2": two worker processes, where the largest cases are derived in
# two stages), SIZES the body counts of the near2 patterns (default "4 5 6";
# SIZES="5 6 7" for the split cases' byte identity at 7 bodies).
#
# The patterns are those of docs/SYMBOLIC.md ("Representation"): the paper's
# four bodies with the seven α's, and 4 to 6 bodies with nearest and
# next-nearest neighbours and their couplings.
set -euo pipefail
old="${1:?usage: derive_side_by_side.sh OLD NEW [RUNS]}"
new="${2:?usage: derive_side_by_side.sh OLD NEW [RUNS]}"
runs="${3:-3}"
read -r -a new_args <<< "${NEW_ARGS:-}"
read -r -a both_args <<< "${ARGS:-}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
seconds() { local t0 t1; t0=$(date +%s.%N); "$@" > /dev/null 2>&1; t1=$(date +%s.%N); echo "$t1 - $t0" | bc; }
measure() {
  local label="$1"; shift
  for ((r = 1; r <= runs; ++r)); do
    local before after same
    before=$(seconds "$old" derive "$@" "${both_args[@]}" --format json -o "$work/old.json")
    after=$(seconds "$new" derive "$@" "${both_args[@]}" "${new_args[@]}" --format json -o "$work/new.json")
    if cmp -s "$work/old.json" "$work/new.json"; then same="same bytes"
    elif python3 - "$work/old.json" "$work/new.json" <<'PY'
import json, sys
def within(old, new):  # every field of the old output is in the new one, with the same value
    if isinstance(old, dict):
        return isinstance(new, dict) and all(k in new and within(v, new[k]) for k, v in old.items())
    if isinstance(old, list):
        return isinstance(new, list) and len(old) == len(new) and all(within(a, b) for a, b in zip(old, new))
    return old == new
sys.exit(0 if within(json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))) else 1)
PY
    then same="old fields unchanged, new fields added"
    else same="DIFFERENT"; fi
    echo "$label run $r: before $before s, after $after s, $same"
  done
}
uptime
measure "n=4 seven alphas" --all --alphas 1,2,3,4,5,6,7
for n in ${SIZES:-4 5 6}; do measure "n=$n near2+coupling" --bodies "$n" --pairs near2 --coupling near2 --all; done
uptime
