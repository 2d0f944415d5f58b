# Shared by the sweep engine tests (parallel_test.sh, slurm_test.sh); sourced, not run.
# Each test makes a sweep of the springs scenario, runs it here with --jobs 2 and on its engine,
# and checks that both gather the same results (wall times aside: they are measurements).

# enter_work_dir NAME: a fresh temporary directory, removed on exit, as the working directory.
enter_work_dir() {
  work=$(mktemp -d "${TMPDIR:-/tmp}/particles_$1_XXXXXX")
  trap 'rm -rf -- "$work"' EXIT
  cd "$work"
}

# write_springs_sweep FILE KS INTEGRATORS DTS [EXTRA]: the springs scenario, half a second per job,
# over the stiffnesses KS crossed with the (integrator, dt) pairs zipped from INTEGRATORS and DTS
# (YAML lists such as "[20, 40]"); EXTRA is appended as further top-level YAML.
write_springs_sweep() {
  cat > "$1" <<YAML
scenarios: [$source_dir/scenarios/springs.yaml]
command: run
options: {duration: 0.5}
parameters:
  - {key: 'forces[1].ks', values: $2}
  - zip:
    - {key: integrator, values: $3}
    - {key: dt, values: $4}
${5:-}
YAML
}

# expect_same_results HERE THERE ENGINE ROWS: the two results.csv agree but for their timing
# columns, and all ROWS rows are ok with exit 0.
expect_same_results() {
  python3 "$source_dir/tests/sweep/without_timings.py" "$1" > here.txt
  python3 "$source_dir/tests/sweep/without_timings.py" "$2" > there.txt
  if ! diff -u here.txt there.txt; then
    echo "the results gathered from $3 differ from those of --jobs 2" >&2
    exit 1
  fi
  local rows ok
  rows=$(($(wc -l < there.txt) - 1))
  ok=$(grep -c ',ok,0,' there.txt || true)
  [ "$rows" -eq "$4" ] && [ "$ok" -eq "$4" ] || { echo "expected $4 ok rows, got $ok of $rows" >&2; exit 1; }
}
