#!/usr/bin/env bash
# GNU parallel runs a sweep's emitted job list unchanged (docs/sweeps.md); what it gathers equals
# what `particles sweep --jobs 2` gathers (wall times aside: they are measurements, not results).
# Usage: parallel_test.sh PARTICLES SOURCE_DIR
set -euo pipefail
particles=$1
source_dir=$2
source "$source_dir/tests/sweep/common.sh"
command -v parallel >/dev/null || { echo "GNU parallel is not installed (scripts/deps test installs it)" >&2; exit 1; }
enter_work_dir parallel

# Ten jobs: five stiffnesses × two (integrator, dt) pairs.
write_springs_sweep sweep.yaml '[20, 35, 50, 65, 80]' '[symplectic_euler, rk4]' '[0.002, 0.01]'

"$particles" sweep sweep.yaml -o here --jobs 2 --quiet
"$particles" sweep sweep.yaml -o there --emit parallel --quiet
jobs=$(wc -l < there/jobs.txt)
[ "$jobs" -eq 10 ] || { echo "expected 10 jobs in jobs.txt, got $jobs" >&2; exit 1; }
parallel --will-cite --joblog there/joblog.txt --jobs 2 < there/jobs.txt > there/parallel.out
"$particles" gather there --quiet

# Every job ran once under parallel and exited 0 (joblog: header + one line per job, Exitval is column 7).
awk -F'\t' 'NR > 1 { n++; if ($7 != 0) bad++ } END { if (n != 10 || bad) { print "joblog: " n " jobs, " bad+0 " failed" > "/dev/stderr"; exit 1 } }' there/joblog.txt

expect_same_results here/results.csv there/results.csv "GNU parallel" 10
echo "GNU parallel ran $jobs jobs; gathered results equal those of --jobs 2 (10 rows)"
