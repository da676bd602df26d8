# Shell functions about Debian's OpenBLAS kernels (sourced by scripts/portability.sh and the
# second-kernel tests): which this CPU can execute, which OpenBLAS runs, and which to compare with.

# The kernels of Prescott, Haswell, Zen, SkylakeX that this CPU can execute (by its /proc/cpuinfo
# flags: Prescott needs SSE3, Haswell and Zen AVX2 and FMA, SkylakeX AVX-512 F/BW/DQ/VL/CD).
supported_kernels() {
  local flags out="Prescott"
  flags=" $(grep -m1 '^flags' /proc/cpuinfo | cut -d: -f2) "
  if [[ $flags == *" avx2 "* && $flags == *" fma "* ]]; then out+=" Haswell Zen"; fi
  if [[ $flags == *" avx512f "* && $flags == *" avx512bw "* && $flags == *" avx512dq "* &&
        $flags == *" avx512vl "* && $flags == *" avx512cd "* ]]; then out+=" SkylakeX"; fi
  echo "$out"
}
kernel_supported() { [[ " $(supported_kernels) " == *" $1 "* ]]; }

# The kernel OpenBLAS runs under the current environment (OPENBLAS_CORETYPE, else the CPU's).
openblas_kernel() {
  python3 - <<'PY' 2>/dev/null || echo unknown
import ctypes
lib = ctypes.CDLL("libopenblas.so.0")
lib.openblas_get_corename.restype = ctypes.c_char_p
print(lib.openblas_get_corename().decode())
PY
}

# A kernel this CPU supports whose arithmetic differs from the one OpenBLAS picks by default:
# Haswell (the AVX2 kernels an AMD Zen machine runs) where the default is an AVX-512 one or
# Prescott (the fallback of an OpenBLAS that does not know the CPU's model, as on some virtual
# machines), Prescott otherwise.
second_kernel() {
  local default
  default=$(env -u OPENBLAS_CORETYPE bash -c "$(declare -f openblas_kernel); openblas_kernel")
  case "$default" in
    SkylakeX|Cooperlake|SapphireRapids|Prescott) kernel_supported Haswell && echo Haswell || echo Prescott ;;
    *) echo Prescott ;;
  esac
}
