# The machine a benchmark ran on, in one line; sourced by the bench scripts:
#   . bench/machine.sh; echo "machine: $(machine_line "$gphr"); ranks $np"
# CPU model, cores (physical cores x hardware threads: ranks on the two threads of one core share
# its FPU and caches), memory, date, the gphr commit, and the BLAS kernels the run used: OpenBLAS
# picks them at load time from the CPU it is told it runs on (OPENBLAS_CORETYPE overrides), and a
# virtual machine that hides its CPU model can get generic kernels - on the 16-core node of
# doc/benchmarks.md the dense (BLAS-3) stages ran at 0.5-0.6x this VM's speed per core while the
# sparse training ran at the same speed. The vector units the CPU reports (avx2, avx512f) say
# which kernels it could have had.

# machine_line [GPHR]: GPHR (a gphr binary, default build/packages/driver/gphr) is asked which
# OpenBLAS kernels it loads.
machine_line() {
  local g=${1:-build/packages/driver/gphr} model cores topo mem describe blas simd
  model=$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)
  cores=$(env -u OMP_NUM_THREADS -u OMP_THREAD_LIMIT nproc)  # GNU nproc honours both
  topo=$(lscpu 2>/dev/null | awk -F: '/^Thread\(s\) per core/ {t = $2} /^Core\(s\) per socket/ {c = $2}
    /^Socket\(s\)/ {s = $2} END {gsub(/ /, "", t); gsub(/ /, "", c); gsub(/ /, "", s); if (c) printf "%d core(s) x %d thread(s)", c * s, t}')
  mem=$(free -m | awk '/Mem/ {printf "%.1f", $2 / 1024}')
  describe=$(git describe --always --dirty 2>/dev/null || echo "not a git checkout")
  # timeout: gphr starts MPI, which can wait for a launcher under a batch system
  blas=$([ -x "$g" ] && OPENBLAS_VERBOSE=2 timeout 10 "$g" --help 2>&1 | sed -n 's/^Core: //p' | head -1)
  simd=$(grep -m1 '^flags' /proc/cpuinfo | tr ' ' '\n' | grep -xE 'avx|avx2|avx512f|fma' | sort | xargs)
  printf '%s, %s cores (%s), %s GiB; %s; gphr %s; OpenBLAS kernels %s (CPU has: %s)' "$model" "$cores" \
    "${topo:-topology unknown}" "$mem" "$(date -u '+%F %H:%M UTC')" "$describe" "${blas:-unknown}" "${simd:-no avx}"
}
