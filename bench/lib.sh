# Shared helpers of the benchmark scripts (sourced, not run).
# Timing uses GNU time -v (/usr/bin/time, or $GNU_TIME): wall clock, user+sys CPU and peak resident set size.

export SUMO_HOME="${SUMO_HOME:-/usr/share/sumo}"

log() { printf '[%s] %s\n' "$(basename "$0")" "$*" >&2; }

# Seconds from GNU time's "h:mm:ss" or "m:ss.ss" elapsed field.
_elapsed_seconds() {
  awk -F: '{ s = 0; for (i = 1; i <= NF; i++) s = s * 60 + $i; printf "%.2f", s }' <<<"$1"
}

# measure LOGFILE CMD...: runs CMD with stdout+stderr in LOGFILE, GNU time's report in LOGFILE.time.
# Prints "wall_s cpu_s rss_mib" and returns CMD's exit status.
measure() {
  local logfile="$1"; shift
  local status=0
  "${GNU_TIME:-/usr/bin/time}" -v -o "$logfile.time" "$@" >"$logfile" 2>&1 || status=$?
  local elapsed user sys rss
  elapsed=$(sed -n 's/^.*Elapsed (wall clock) time (h:mm:ss or m:ss): //p' "$logfile.time")
  user=$(sed -n 's/^.*User time (seconds): //p' "$logfile.time")
  sys=$(sed -n 's/^.*System time (seconds): //p' "$logfile.time")
  rss=$(sed -n 's/^.*Maximum resident set size (kbytes): //p' "$logfile.time")
  if [[ -z "$elapsed" || -z "$rss" ]]; then
    echo "nan nan nan"
    return 127
  fi
  printf '%s %.2f %.1f\n' "$(_elapsed_seconds "$elapsed")" \
    "$(awk -v u="$user" -v s="$sys" 'BEGIN { print u + s }')" \
    "$(awk -v k="$rss" 'BEGIN { print k / 1024 }')"
  return "$status"
}

# median VALUES...: the middle value (mean of the two middle ones for an even count).
median() {
  printf '%s\n' "$@" | sort -g | awk '{ v[NR] = $1 }
    END { if (NR == 0) { print "nan"; exit }
          if (NR % 2) printf "%.3f\n", v[(NR + 1) / 2]
          else printf "%.3f\n", (v[NR / 2] + v[NR / 2 + 1]) / 2 }'
}

# ratio A B: A / B with two decimals, "n/a" when either is missing or B is zero.
ratio() {
  awk -v a="$1" -v b="$2" 'BEGIN {
    number = "^[0-9]*[.]?[0-9]+([eE][-+]?[0-9]+)?$"
    if (a !~ number || b !~ number || b + 0 == 0) print "n/a"
    else printf "%.2f\n", a / b }'
}

# Clock and cache/memory latencies of this machine now (see bench/host_probe.cpp); built on first use.
host_probe() {
  local dir src bin
  dir="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
  src="$dir/host_probe.cpp"
  bin="$dir/work/host_probe"
  if [[ ! -x "$bin" || "$src" -nt "$bin" ]]; then
    command -v g++ >/dev/null || { echo "unavailable (no g++)"; return; }
    mkdir -p "$dir/work"
    g++ -O2 -std=c++20 "$src" -o "$bin" || { echo "unavailable (build failed)"; return; }
  fi
  "$bin"
}

machine_info() {
  local cpu
  cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1)
  # The model name is masked on these VMs; family/model, clock and L3 tell host generations apart.
  cpu="$cpu (family $(sed -n 's/^cpu family[[:space:]]*: //p' /proc/cpuinfo | head -n 1)"
  cpu="$cpu model $(sed -n 's/^model[[:space:]]*: //p' /proc/cpuinfo | head -n 1)"
  cpu="$cpu, $(sed -n 's/^cpu MHz[[:space:]]*: //p' /proc/cpuinfo | head -n 1) MHz"
  cpu="$cpu, L3 $(lscpu 2>/dev/null | sed -n 's/^L3 cache:[[:space:]]*//p' | head -n 1))"
  echo "- date: $(date -u '+%Y-%m-%d %H:%M:%S UTC')"
  echo "- host: nproc=$(nproc), CPU: ${cpu:-unknown}, memory: $(awk '/MemTotal/ { printf "%.1f GiB", $2 / 1048576 }' /proc/meminfo)"
  echo "- load average at start: $(cut -d' ' -f1-3 /proc/loadavg)"
  echo "- host probe (bench/host_probe.cpp): $(host_probe)"
  echo "- $(sumo --version 2>/dev/null | head -n 1)"
  echo "- lpsim commit: ${LPSIM_COMMIT:-$(git -C "$(dirname "${BASH_SOURCE[0]}")" rev-parse --short HEAD 2>/dev/null || echo unknown)}"
}
