# sandbox sweep (README, "Sweeps"): the command-line contract, then whole sweeps through the shell.
set(SWEEP_OUT ${CMAKE_CURRENT_BINARY_DIR}/sweep_out)
set(SWEEP_DATA ${CMAKE_CURRENT_SOURCE_DIR}/sweep_data)
cli_test(sweep_help 0 "plan" sweep --help)
cli_test(sweep_bad_shard 2 "--shard: '3/2': out of range" sweep run ${SWEEP_DATA}/two_cases.jsonl --shard 3/2
         --out ${SWEEP_OUT}/x)
cli_test(sweep_missing_plan 2 "/no/such/plan.jsonl: cannot read" sweep run /no/such/plan.jsonl --out ${SWEEP_OUT}/x)
cli_test(sweep_malformed_plan 2 "bad_overrides.jsonl:3: field 'overrides': must be an array of strings" sweep run
         ${SWEEP_DATA}/bad_overrides.jsonl --out ${SWEEP_OUT}/x)
cli_test(sweep_truncated_plan 2 "truncated.jsonl: the header says 2 cases, the file has 1" sweep run
         ${SWEEP_DATA}/truncated.jsonl --out ${SWEEP_OUT}/x)
cli_test(sweep_merge_no_folder 2 "/no/such/runs: no such folder" sweep merge /no/such/runs --out ${SWEEP_OUT}/x)
cli_test(sweep_merge_not_a_run 2 "sweep_data/plan.jsonl: missing" sweep merge ${SWEEP_DATA} --out ${SWEEP_OUT}/x)
cli_test(sweep_plan_unknown_key 2 "vehicle.start.sped_kmh: unknown key" sweep plan custom --scene wall_crash
         --vary vehicle.start.sped_kmh=20,40 --out ${SWEEP_OUT}/never.jsonl)
cli_test(sweep_plan_bad_vary 2 "--vary: 'speed': expected key=v1,v2" sweep plan custom --scene wall_crash
         --vary speed --out ${SWEEP_OUT}/never.jsonl)
cli_test(sweep_plan_no_folder 2 "--out: no folder /no/such" sweep plan custom --scene wall_crash
         --vary physics_hz=500 --out /no/such/plan.jsonl)
cli_test(sweep_plan_tradeoff_two_cars 2 "car_to_car.json: tradeoff measures one car" sweep plan tradeoff
         --scene car_to_car --quick --out ${SWEEP_OUT}/never.jsonl)

# Whole sweeps (each a few tens of seconds here): killed and resumed, refused merges, failures,
# provenance; the sharded trade-off study against the one-process one.
add_test(NAME cli.sweep_resume COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/sweep_resume.sh ${SANDBOX}
         ${SWEEP_OUT}/resume resume)
add_test(NAME cli.sweep_refusals COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/sweep_resume.sh ${SANDBOX}
         ${SWEEP_OUT}/resume refusals)
set_tests_properties(cli.sweep_resume PROPERTIES FIXTURES_SETUP sweep_resumed)
set_tests_properties(cli.sweep_refusals PROPERTIES FIXTURES_REQUIRED sweep_resumed)
# The shards, parallel and Slurm tests compare with the one-process result of cli.sweep_tradeoff_one.
add_test(NAME cli.sweep_tradeoff_one COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/sweep_tradeoff.sh ${SANDBOX}
         ${SWEEP_OUT}/tradeoff_one one)
set_tests_properties(cli.sweep_tradeoff_one PROPERTIES FIXTURES_SETUP tradeoff_one_process)
set(TRADEOFF_ONE ONE_PROCESS_DIR=${SWEEP_OUT}/tradeoff_one/one)
add_test(NAME cli.sweep_tradeoff_shards COMMAND env ${TRADEOFF_ONE} bash ${CMAKE_CURRENT_SOURCE_DIR}/sweep_tradeoff.sh
         ${SANDBOX} ${SWEEP_OUT}/tradeoff_shards shards)
set_tests_properties(cli.sweep_tradeoff_shards PROPERTIES FIXTURES_REQUIRED tradeoff_one_process)
add_test(NAME cli.sweep_tradeoff_parallel COMMAND env ${TRADEOFF_ONE} bash ${CMAKE_CURRENT_SOURCE_DIR}/sweep_tradeoff.sh
         ${SANDBOX} ${SWEEP_OUT}/tradeoff_parallel parallel)
set_tests_properties(cli.sweep_tradeoff_parallel PROPERTIES SKIP_RETURN_CODE 77 FIXTURES_REQUIRED tradeoff_one_process)
add_test(NAME cli.sweep_converge COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/sweep_kind.sh ${SANDBOX}
         ${SWEEP_OUT}/converge converge converge.csv --quick --set duration_s=0.4)
add_test(NAME cli.sweep_stress COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/sweep_kind.sh ${SANDBOX}
         ${SWEEP_OUT}/stress stress stress.csv --quick --group meshes --group impact_speed)
# The grid is mostly timings; its sharded merge is compared with cli.bench_grid_quick's output.
add_test(NAME cli.sweep_grid COMMAND env ONE_PROCESS_DIR=${RUN_OUT}/grid bash ${CMAKE_CURRENT_SOURCE_DIR}/sweep_kind.sh
         ${SANDBOX} ${SWEEP_OUT}/grid grid grid.csv --quick)
set_tests_properties(cli.bench_grid_quick PROPERTIES FIXTURES_SETUP grid_one_process)
set_tests_properties(cli.sweep_grid PROPERTIES FIXTURES_REQUIRED grid_one_process)
# Nothing written by a refused plan.
add_test(NAME cli.sweep_plan_refused_writes_nothing COMMAND test ! -e ${SWEEP_OUT}/never.jsonl)
set_tests_properties(cli.sweep_plan_refused_writes_nothing PROPERTIES DEPENDS
                     "cli.sweep_plan_unknown_key;cli.sweep_plan_bad_vary;cli.sweep_plan_tradeoff_two_cars")

# The real scheduler: a one-node Slurm started for the test (tools/sweep/local-slurm.sh), a small trade-off
# plan as a 4-task job array and the dependent merge (tools/sweep/submit.sh). Skipped, visibly, when Slurm
# cannot be started (not root, packages missing).
add_test(NAME cli.sweep_slurm_cluster COMMAND env ${TRADEOFF_ONE} bash ${CMAKE_CURRENT_SOURCE_DIR}/sweep_slurm.sh
         ${SANDBOX} ${SWEEP_OUT}/slurm)
set_tests_properties(cli.sweep_slurm_cluster PROPERTIES LABELS cluster SKIP_RETURN_CODE 77 TIMEOUT 600
                     FIXTURES_REQUIRED tradeoff_one_process)
