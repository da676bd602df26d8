#!/usr/bin/env bash
# Makes the pictures the documentation shows, from the SWE example on 2 ranks:
#   doc/img/fields_swe.png     its fields.png (README.md)
#   doc/img/paraview_swe.png   its fields.xdmf in ParaView (doc/reference.md; needs Debian's
#                              paraview and python3-paraview (setup.sh --tests installs them) and xvfb)
# usage: bash scripts/doc_pictures.sh   (after scripts/setup.sh)
set -eu
cd "$(dirname "$0")/.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
mpirun -np 2 build/packages/driver/gphr run examples/gp-deim_swe.yaml --output "$work/swe" > /dev/null
cp "$work/swe/fields.png" doc/img/fields_swe.png
# The most accurate GP-DEIM run's difference field (output.fieldModels' best).
difference=$(grep -o 'Name="chi_gp-deim_[^"]*_minus_fom"' "$work/swe/fields.xdmf" | head -1 | cut -d'"' -f2)
xvfb-run -a -s "-screen 0 1600x1200x24" pvbatch scripts/paraview_picture.py "$work/swe/fields.xdmf" "$difference" \
  doc/img/paraview_swe.png > /dev/null
echo "doc/img/fields_swe.png, doc/img/paraview_swe.png written from examples/gp-deim_swe.yaml ($difference)"
