#!/usr/bin/env bash
# GNU parallel runs a sweep's emitted job list unchanged (docs/sweeps.md); what it gathers equals
# what `particles sweep --jobs 2` gathers (wall times aside: they are measurements, not results).
# Usage: parallel_test.sh PARTICLES SOURCE_DIR
set -euo pipefail
particles=$1
source_dir=$2
command -v parallel >/dev/null || { echo "GNU parallel is not installed (scripts/deps installs it)" >&2; exit 1; }
work=$(mktemp -d "${TMPDIR:-/tmp}/particles_parallel_XXXXXX")
trap 'rm -rf -- "$work"' EXIT
cd "$work"

# Ten jobs: the springs scenario over stiffness × (integrator, dt) pairs, half a second each.
cat > sweep.yaml <<YAML
scenarios: [$source_dir/scenarios/springs.yaml]
command: run
options: {duration: 0.5}
parameters:
  - {key: 'forces[1].ks', values: [20, 35, 50, 65, 80]}
  - zip:
    - {key: integrator, values: [symplectic_euler, rk4]}
    - {key: dt, values: [0.002, 0.01]}
YAML

"$particles" sweep sweep.yaml -o here --jobs 2 --quiet
"$particles" sweep sweep.yaml -o there --emit parallel --quiet
jobs=$(wc -l < there/jobs.txt)
[ "$jobs" -eq 10 ] || { echo "expected 10 jobs in jobs.txt, got $jobs" >&2; exit 1; }
parallel --will-cite --joblog there/joblog.txt --jobs 2 < there/jobs.txt > there/parallel.out
"$particles" gather there --quiet

# Every job ran once under parallel and exited 0 (joblog: header + one line per job, Exitval is column 7).
awk -F'\t' 'NR > 1 { n++; if ($7 != 0) bad++ } END { if (n != 10 || bad) { print "joblog: " n " jobs, " bad+0 " failed" > "/dev/stderr"; exit 1 } }' there/joblog.txt

# The two tables, without the columns that are timings.
strip() { python3 "$source_dir/tests/sweep/without_timings.py" "$1"; }
strip here/results.csv > here.txt
strip there/results.csv > there.txt
if ! diff -u here.txt there.txt; then
  echo "the results gathered from GNU parallel differ from those of --jobs 2" >&2
  exit 1
fi
rows=$(($(wc -l < here.txt) - 1))
ok=$(grep -c ',ok,0,' here.txt || true)
[ "$rows" -eq 10 ] && [ "$ok" -eq 10 ] || { echo "expected 10 ok rows, got $ok of $rows" >&2; exit 1; }
echo "GNU parallel ran $jobs jobs; gathered results equal those of --jobs 2 ($rows rows)"
