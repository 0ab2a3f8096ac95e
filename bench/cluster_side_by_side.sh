#!/usr/bin/env bash
# Wall time of a long command run three ways, side by side (alternating, RUNS
# runs each): 1 process x 1 worker, 1 process x 2 workers, 2 MPI ranks x 1
# worker each; whether each output is the bytes of the first; then the parts
# of the run that do not spread over ranks (docs/PERFORMANCE.md, "On several
# machines"):
#
#   bench/cluster_side_by_side.sh SUPERBALL_BUILT_WITH_MPI [RUNS]
#
#  - the per-task times: the run on one worker with --checkpoint, the times
#    between the task files' modification times (the first task's from the
#    checkpoint folder's run file, written before any task starts);
#  - the serial part: `superball merge` of the run's one part (--shard 1/1):
#    the set-up, the results in task order and the output written, no task
#    computed;
#  - verify --case 1's stages: its drawn points alone, and its set-up;
#  - the start of MPI: mpirun -n 2 of a two-value sweep.
set -euo pipefail
exe="${1:?usage: cluster_side_by_side.sh SUPERBALL [RUNS]}"
runs="${2:-5}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
# --bind-to none: on a node shared with other jobs a rank pinned to one core (Open MPI binds when
# there are at most 2 ranks) waits for that core while the other may be free.
mpirun=(mpirun --oversubscribe --allow-run-as-root --bind-to none)
scene="$(dirname "$0")/../cases/scenes/paper-4.4-alpha2.toml"
seconds() { local t0 t1; t0=$(date +%s.%N); "$@" > "$work/out" 2> /dev/null; t1=$(date +%s.%N); echo "$t1 - $t0" | bc; }
median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2 ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2)}'; }
# measure LABEL WORKERS_OPTION ARGS...: the three ways, RUNS times each, alternating.
measure() {
  local label="$1" opt="$2"; shift 2
  : > "$work/t11"; : > "$work/t12"; : > "$work/t21"
  for ((r = 1; r <= runs; ++r)); do
    seconds "$exe" "$@" "$opt" 1 >> "$work/t11"; cp "$work/out" "$work/ref"
    seconds "$exe" "$@" "$opt" 2 >> "$work/t12"; cmp -s "$work/out" "$work/ref" || echo "$label: 1x2 output DIFFERENT"
    seconds "${mpirun[@]}" -n 2 "$exe" "$@" "$opt" 1 >> "$work/t21"; cmp -s "$work/out" "$work/ref" || echo "$label: 2x1 output DIFFERENT"
  done
  local a b c
  a=$(median < "$work/t11"); b=$(median < "$work/t12"); c=$(median < "$work/t21")
  echo "$label: median of $runs, 1x1 $a s, 1x2 $b s (speed-up $(echo "scale=2; $a / $b" | bc)), 2 ranks x1 $c s (speed-up $(echo "scale=2; $a / $c" | bc)); same bytes each way unless said"
}
# tasks LABEL ARGS...: per-task times on one worker, from the checkpoint's file times.
tasks() {
  local label="$1"; shift
  rm -rf "$work/ck"
  "$exe" "$@" --checkpoint "$work/ck" > /dev/null
  python3 - "$work/ck" "$label" <<'PY'
import os, sys
d, label = sys.argv[1], sys.argv[2]
start = os.stat(os.path.join(d, "run")).st_mtime_ns
ends = sorted(os.stat(os.path.join(d, f)).st_mtime_ns for f in os.listdir(d) if f.startswith("task-"))
times = [(b - a) / 1e9 for a, b in zip([start] + ends[:-1], ends)]
print(f"{label}: {len(times)} tasks on one worker, sum {sum(times):.3f} s, largest {max(times):.3f} s, "
      f"median {sorted(times)[len(times) // 2]:.4f} s")
PY
  "$exe" "$@" --shard 1/1 --part "$work/one.part" > /dev/null
  local t
  t=$(for ((r = 1; r <= runs; ++r)); do seconds "$exe" merge "$work/one.part"; done | median)
  echo "$label: serial part (merge of its one part: set-up, results in order, output of $(wc -c < "$work/out") bytes): median $t s"
}
uptime
derive=(derive --bodies 6 --pairs near2 --coupling near2 --all --format json)
measure "derive 6 bodies near2" --jobs "${derive[@]}"
tasks "derive 6 bodies near2" "${derive[@]}" --jobs 1
verify=(verify --case 1 --alphas 2)
measure "verify --case 1 --alphas 2 (one case, its blocks of points spread)" --threads "${verify[@]}"
# Its two stages (50 tasks of drawn points, then 20 boundary searches) and its set-up, on one thread.
t=$(for ((r = 1; r <= runs; ++r)); do seconds "$exe" "${verify[@]}" --threads 1 --boundary-pairs 0; done | median)
echo "verify --case 1 --alphas 2: the drawn points alone (--boundary-pairs 0), one thread, median $t s"
t=$(for ((r = 1; r <= runs; ++r)); do seconds "$exe" "${verify[@]}" --threads 1 --samples 1 --boundary-pairs 0 --epsilons 1e-2; done | median)
echo "verify --case 1 --alphas 2: the set-up (one point), median $t s"
sweep=(sweep "$scene" --vary K.3-4=0:20:16385 --switch-points)
measure "sweep switch points, 16385 values" --threads "${sweep[@]}"
tasks "sweep switch points, 16385 values" "${sweep[@]}" --threads 1
t=$(for ((r = 1; r <= runs; ++r)); do seconds "${mpirun[@]}" -n 2 "$exe" sweep "$scene" --vary K.3-4=0:20:2; done | median)
echo "start of MPI: mpirun -n 2 of a two-value sweep, median $t s"
uptime
