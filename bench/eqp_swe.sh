#!/usr/bin/env bash
# The SWE case of bench/eqp.sh (SWE 20 x 20, T = 2, IMR, 3 x 3 training, 2k = 40; rom, gp-deim,
# gp-eqp, gp-eqp-refit at m in M, default 6 10 20 40 60).
# usage: bash bench/eqp_swe.sh [RANKS] [BUILD_DIR]
exec bash "$(dirname "$0")/eqp.sh" swe "$@"
