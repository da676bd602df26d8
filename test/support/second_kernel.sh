#!/usr/bin/env bash
# Runs a command under a second OpenBLAS kernel, one this CPU supports whose arithmetic differs from
# the kernel OpenBLAS picks by default (scripts/openblas_kernels.sh): the suite's end-to-end tests
# most sensitive to the last bits of the BLAS run once more this way, so that a test that holds
# only on the developer's kernel fails here, not on a user's machine (doc/portability.md).
# usage: second_kernel.sh COMMAND [ARGS...]
set -u
source "$(dirname "$0")/../../scripts/openblas_kernels.sh"
OPENBLAS_CORETYPE=$(second_kernel)
export OPENBLAS_CORETYPE
echo "[second kernel] OPENBLAS_CORETYPE=$OPENBLAS_CORETYPE (OpenBLAS runs $(openblas_kernel); default on this CPU: $(env -u OPENBLAS_CORETYPE bash -c "$(declare -f openblas_kernel); openblas_kernel"))"
exec "$@"
