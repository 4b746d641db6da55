#!/usr/bin/env bash
# Runs the GPU checks and benchmarks on a lent GPU machine that has CUDA but no package registry, from a
# CUDA build made elsewhere and carried along (bench/prepare_gpu_build.sh makes it and lists what to carry):
#   build-gpu/: cmake -DLPSIM_CUDA=ON -DCMAKE_CUDA_ARCHITECTURES=90, Ninja, Release;
#   build-gpu/libs.tar.xz: the shared libraries lpsim needs that such a machine may lack (all but the C and
#                    C++ runtimes) and GNU time as gnu-time, unpacked into build-gpu/libs/;  build-gpu/bayarea/lpsim_bayarea_tertiary: the base network.
# The tests have the repository's absolute path compiled in: where the copy lies elsewhere, a link stands in.
#
# Usage: bench/gpu_machine.sh tests|bench [regional_bench.sh options...]
#        bench/gpu_machine.sh all [seconds, default 360]
#        bench/gpu_machine.sh parts [end, default 3600]
#        bench/gpu_machine.sh scenario CONFIG [run options]
#        bench/gpu_machine.sh assign [iterations, default 3] [end, default 3600]
# `parts` runs the partitioned engine on the GPU (the parts in one process share it): grid_tls and the regional
# 1M trips' first hour (bench/work/regional/1000000/regional.lpsim, made by `bench` when missing) in 1, 2 and
# 4 parts with --device gpu, and prints each run's wall time, updates/s and per-part line, and whether the
# tripinfo of 2 and 4 parts equals 1 part's.
# `all` is the whole device check in one call, in order of value, each part started only while the budget
# leaves room for it: the GPU tests; the 9M-trip day on the GPU with the CPU backend on the same snapshot
# (first 600 s); the 1M and 3M days on the GPU. Its reports and logs go to $OUT (8 files at most), else to
# bench/work/gpu_all. A lease is 15 minutes of device time with the machine's start: keep the budget so
# that a second, shorter call still fits.
set -uo pipefail
cd "$(dirname "$0")/.."
here=$PWD
build=${BUILD:-build-gpu}
# prepare_gpu_build.sh packs the libraries: unpack them once.
[[ -f "$build/libs.tar.xz" && ! -d "$build/libs" ]] && tar -C "$build" -xJf "$build/libs.tar.xz"
export LD_LIBRARY_PATH=$here/$build/libs${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
export GNU_TIME=$here/$build/libs/gnu-time
# The device copy's git metadata is not this build's: prepare_gpu_build.sh wrote the commit it built.
[[ -f "$build/COMMIT" ]] && export LPSIM_COMMIT=$(cat "$build/COMMIT")
origin=$(sed -n 's/^CMAKE_HOME_DIRECTORY:INTERNAL=//p' "$build/CMakeCache.txt")
if [[ -n "$origin" && "$origin" != "$here" && ! -e "$origin" ]]; then
  mkdir -p "$(dirname "$origin")" && ln -s "$here" "$origin"
fi
nvidia-smi --query-gpu=name,memory.total,driver_version,clocks.sm,clocks.max.sm --format=csv
what=${1:-tests}
shift || true
case "$what" in
  tests)
    "$build/lpsim" run -c scenarios/grid_tls/grid_tls.sumocfg --device gpu --end 5 | head -n 3
    "$build/tests/lpsim_gpu_tests" --gtest_color=no
    ;;
  bench)
    bench/regional_bench.sh --lpsim "$build/lpsim" --bayarea "$build/bayarea/lpsim_bayarea_tertiary" "$@"
    ;;
  all)
    budget=${1:-360}
    out=${OUT:-bench/work/gpu_all}
    mkdir -p "$out"
    regional=bench/work/regional
    left() { echo $((budget - SECONDS)); }
    SECONDS=0
    nvidia-smi >"$out/nvidia-smi.txt" 2>&1
    echo "== tests (budget ${budget} s)"
    timeout 150 "$0" tests >"$out/tests.log" 2>&1
    echo "tests: exit $? after $SECONDS s; $(grep -E '^\[  (PASSED|FAILED) ' "$out/tests.log" | paste -sd' ')"
    # The 9M day: generation ~30 s, conversion ~30 s, the GPU day ~100 s, the CPU's first 600 s.
    if (($(left) > 150)); then
      echo "== 9M trips, GPU day and CPU first 600 s"
      timeout "$(left)" "$0" bench --trips 9000000 --devices "gpu cpu" --cpu-end 600 --runs 1 --warmup 0 \
        >"$out/bench_9m.log" 2>&1
      echo "9M: exit $? after $SECONDS s"
      cp "$regional/results.md" "$out/regional_9m.md" 2>/dev/null
      cp "$regional/9000000/gpu.log" "$out/gpu_9m.log" 2>/dev/null
    fi
    if (($(left) > 120)); then
      echo "== 1M and 3M trips, GPU days"
      timeout "$(left)" "$0" bench --trips "1000000 3000000" --devices gpu --runs 1 --warmup 0 \
        >"$out/bench_1m_3m.log" 2>&1
      echo "1M, 3M: exit $? after $SECONDS s"
      cp "$regional/results.md" "$out/regional_1m_3m.md" 2>/dev/null
    fi
    # Each regional report names its runs' logs; the bench logs hold their progress lines.
    tail -n 40 "$out"/regional_*.md 2>/dev/null
    ;;
  parts)
    end=${1:-3600}
    out=${OUT:-bench/work/gpu_parts}
    mkdir -p "$out"
    snapshot=bench/work/regional/1000000/regional.lpsim
    [[ -f $snapshot ]] || "$0" bench --trips 1000000 --devices gpu --runs 1 --warmup 0 >"$out/make_regional.log" 2>&1
    for input in "-c scenarios/grid_tls/grid_tls.sumocfg" "$snapshot --end $end"; do
      for k in 1 2 4; do
        # shellcheck disable=SC2086
        "$build/lpsim" run $input --device gpu --parts "$k" --parts.min-vehicles 0 --no-step-log --no-warnings \
          --tripinfo-output "$out/trip_$k.xml" >"$out/run_$k.log" 2>&1
        echo "== $input, $k parts: exit $?"
        grep -E "Duration|UPS|Part " "$out/run_$k.log"
      done
      for k in 2 4; do cmp -s "$out/trip_1.xml" "$out/trip_$k.xml" && echo "$k parts: tripinfo identical" ||
        echo "$k parts: tripinfo DIFFERS"; done
    done
    ;;
  assign)
    # The regional assignment's cost per iteration on the GPU: the 1M trips' first hour (0.5 s steps)
    # simulated alone, then `lpsim assign` of that hour (CH) for N iterations; each iteration's line (routing
    # and simulation CPU) with the whole run's wall and CPU time beside the hour alone's. The snapshot is
    # converted here from bench/work/regional_1m_csv.tar.xz when that was carried (its CSVs), else made by
    # `bench`.
    iterations=${1:-3}
    end=${2:-3600}
    out=${OUT:-bench/work/gpu_assign}
    mkdir -p "$out"
    dir=bench/work/regional/1000000
    snapshot=$dir/regional.lpsim
    if [[ ! -f $snapshot && -f bench/work/regional_1m_csv.tar.xz ]]; then
      mkdir -p "$dir" && tar -C "$dir" -xJf bench/work/regional_1m_csv.tar.xz
      "$build/lpsim" convert --lpsim-nodes "$dir/nodes.csv" --lpsim-edges "$dir/edges.csv" \
        --lpsim-od "$dir/od.csv" --threads "$(nproc)" -o "$snapshot" >"$out/convert.log" 2>&1
      echo "convert: exit $? after $SECONDS s"
    fi
    [[ -f $snapshot ]] || "$0" bench --trips 1000000 --devices gpu --runs 1 --warmup 0 >"$out/make_regional.log" 2>&1
    timing="wall %e s, CPU %U user + %S sys s, peak RSS %M KiB"
    "$GNU_TIME" -f "hour alone: $timing" "$build/lpsim" run "$snapshot" --end "$end" --step-length 0.5 \
      --device gpu --threads "$(nproc)" --no-step-log --no-warnings >"$out/run.log" 2>&1
    echo "run: exit $?"
    grep -E "Duration|hour alone" "$out/run.log"
    "$GNU_TIME" -f "assign: $timing" "$build/lpsim" assign "$snapshot" --end "$end" --step-length 0.5 \
      --routing-algorithm CH --iterations "$iterations" --device gpu --threads "$(nproc)" \
      -o "$out/assigned.rou.xml" >"$out/assign.log" 2>&1
    echo "assign: exit $?"
    grep -vE "^(routes|alternatives):" "$out/assign.log" | tail -n $((iterations + 3))
    ;;
  scenario)
    # One scenario on the GPU and on the CPU backend (2 threads): each run's report lines and whether their
    # tripinfo outputs are identical. Further options go to both runs.
    cfg=$1
    shift
    out=${OUT:-bench/work/gpu_scenario}
    mkdir -p "$out"
    for dev in gpu cpu; do
      "$build/lpsim" run -c "$cfg" --device "$dev" --threads 2 --no-step-log --no-warnings \
        --tripinfo-output "$out/trip_$dev.xml" "$@" >"$out/run_$dev.log" 2>&1
      echo "== $cfg on $dev: exit $?"
      grep -E "Duration|UPS|Inserted|Teleports|routing" "$out/run_$dev.log"
    done
    cmp -s "$out/trip_gpu.xml" "$out/trip_cpu.xml" && echo "tripinfo identical" || echo "tripinfo DIFFERS"
    ;;
  *) echo "usage: $0 tests|bench|all|parts|scenario|assign [options]" >&2; exit 2 ;;
esac
