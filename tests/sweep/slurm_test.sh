#!/usr/bin/env bash
# A one-node Slurm cluster (munged, slurmctld, slurmd, started here by tests/slurm/one_node_slurm.sh
# and stopped by their pids) runs a sweep's emitted job array with `sbatch --wait`; what it gathers
# equals what `particles sweep --jobs 2` gathers (wall times aside). Exit 77 (CTest: skipped) with
# the reason printed, and written to skipped-tests.txt beside the program for scripts/test to show,
# only where the daemons cannot start.
# Usage: slurm_test.sh PARTICLES SOURCE_DIR
set -euo pipefail
particles=$1
source_dir=$2
source "$source_dir/tests/sweep/common.sh"
skip_log="$(dirname "$particles")/skipped-tests.txt"
for tool in sbatch slurmctld slurmd munged; do
  command -v "$tool" >/dev/null || { echo "$tool is not installed (scripts/deps test installs slurm-wlm and munge)" >&2; exit 1; }
done
enter_work_dir slurm
mkdir cluster

# Eight jobs: four stiffnesses × two (integrator, dt) pairs, with an extra #SBATCH line.
write_springs_sweep sweep.yaml '[20, 40, 60, 80]' '[verlet, rk4]' '[0.002, 0.01]' 'slurm: [--time=00:05:00]'

"$particles" sweep sweep.yaml -o here --jobs 2 --quiet
"$particles" sweep sweep.yaml -o array --emit slurm --quiet
grep -q '^#SBATCH --array=0-7$' array/sweep.sbatch || { echo "sweep.sbatch: no --array=0-7" >&2; exit 1; }
grep -q '^#SBATCH --time=00:05:00$' array/sweep.sbatch || { echo "sweep.sbatch: the slurm: line is missing" >&2; exit 1; }

set +e
bash "$source_dir/tests/slurm/one_node_slurm.sh" "$work/cluster" -- sbatch --wait array/sweep.sbatch > cluster.out 2>&1
status=$?
set -e
cat cluster.out
if [ "$status" -eq 77 ]; then
  reason=$(grep -m1 '^SKIP:' cluster.out || echo "SKIP: the Slurm daemons did not start")
  echo "sweep:slurm skipped: ${reason#SKIP: }" | tee -a "$skip_log"
  exit 77
fi
[ "$status" -eq 0 ] || { echo "sbatch --wait exited $status" >&2; cat array/logs/* >&2 2>/dev/null || true; exit 1; }

# Each of the 8 tasks ran under Slurm (its own log) and left its job's record.
logs=$(find array/logs -name 'slurm-*_*.log' | wc -l)
records=$(find array/jobs -name record.txt | wc -l)
[ "$logs" -eq 8 ] && [ "$records" -eq 8 ] || { echo "expected 8 task logs and 8 records, got $logs and $records" >&2; exit 1; }

"$particles" gather array --quiet
expect_same_results here/results.csv array/results.csv "the Slurm array" 8
echo "Slurm ran the array of 8 tasks; gathered results equal those of --jobs 2 (8 rows)"
