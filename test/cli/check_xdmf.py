#!/usr/bin/env python3
"""Checks an XDMF file of gphr against the HDF5 file it names, as a reader would open it.

usage: check_xdmf.py FILE.xdmf TIMES_DATASET [--fields a,b,...] [--initial swe2d:BETA | nls1d [--of MODEL]]

- the file parses as XML: Xdmf > Domain > one temporal collection of uniform grids, each with a
  Time, a 3DCoRectMesh topology, an ORIGIN_DXDYDZ geometry and node-centred scalar attributes;
- every attribute is a hyperslab (start, stride, count) of an HDF5 dataset that exists in the named
  file with the stated shape, lies inside it and holds exactly one value per grid point, shaped as
  the grid (ParaView's XDMF Reader reads a hyperslab shaped otherwise short);
- the Time values are those of TIMES_DATASET in that file, in order;
- each field named X_minus_fom equals X minus the full model's field of its component;
- --fields: these fields exist at every time; --initial: the first fields of MODEL (fom) at the
  grid's coordinates is the scene's known initial state (SWE chi0 = 1 + exp(-beta r^2) / 2, NLS
  |u0| = sqrt(2) / cosh x), which only a right origin, spacing and point order give.
"""
import math
import os
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def numbers(item, kind=float):
    return [kind(x) for x in item.text.split()]


def read_attribute(attr, here, files, dims):
    name = attr.get("Name")
    if attr.get("Center") != "Node" or attr.get("AttributeType") != "Scalar":
        fail(f"{name}: not a node-centred scalar")
    slab = attr.find("DataItem")
    if slab is None or slab.get("ItemType") != "HyperSlab":
        fail(f"{name}: not a hyperslab")
    sel, heavy = slab.findall("DataItem")
    start, stride, count = np.array(numbers(sel, int)).reshape(3, 2)
    if heavy.get("Format") != "HDF":
        fail(f"{name}: heavy data not in HDF5")
    path, dataset = heavy.text.strip().rsplit(":", 1)
    rows, width = (int(x) for x in heavy.get("Dimensions").split())
    full = os.path.join(here, path)
    if full not in files:
        if not os.path.exists(full):
            fail(f"{name}: HDF5 file {full} missing")
        files[full] = h5py.File(full, "r")
    f = files[full]
    if dataset not in f:
        fail(f"{name}: dataset {dataset} not in {full}")
    if f[dataset].shape != (rows, width):
        fail(f"{name}: {dataset} has shape {f[dataset].shape}, the XDMF says {(rows, width)}")
    if any(start < 0) or list(stride) != [1, 1] or any(start + count > [rows, width]):
        fail(f"{name}: hyperslab {start} {count} outside {(rows, width)}")
    if int(np.prod(count)) != int(np.prod(dims)) or [int(x) for x in slab.get("Dimensions").split()] != dims:
        fail(f"{name}: {count} values shaped {slab.get('Dimensions')} for a grid of {dims} points")
    return f[dataset][start[0], start[1]:start[1] + count[1]]


def main():
    xdmf, times_dataset = sys.argv[1], sys.argv[2]
    opts = dict(zip(sys.argv[3::2], sys.argv[4::2]))
    here = os.path.dirname(os.path.abspath(xdmf))
    root = ET.parse(xdmf).getroot()
    if root.tag != "Xdmf":
        fail("root element is not Xdmf")
    series = root.find("Domain/Grid")
    if series is None or series.get("CollectionType") != "Temporal":
        fail("no temporal collection")
    files, steps = {}, []
    for grid in series.findall("Grid"):
        topo = grid.find("Topology")
        if topo.get("TopologyType") != "3DCoRectMesh":
            fail("topology " + topo.get("TopologyType"))
        dims = [int(x) for x in topo.get("Dimensions").split()]
        geo = grid.find("Geometry")
        if geo.get("GeometryType") != "ORIGIN_DXDYDZ":
            fail("geometry " + geo.get("GeometryType"))
        origin, spacing = (numbers(d) for d in geo.findall("DataItem"))
        fields = {a.get("Name"): read_attribute(a, here, files, dims) for a in grid.findall("Attribute")}
        steps.append((float(grid.find("Time").get("Value")), dims, origin, spacing, fields))
    if not steps:
        fail("no time in the series")
    h5 = next(iter(files.values()))
    expected = h5[times_dataset][...].ravel()
    if [s[0] for s in steps] != list(expected):
        fail(f"times {[s[0] for s in steps]} are not {times_dataset} {list(expected)}")
    wanted = [x for x in opts.get("--fields", "").split(",") if x]
    for t, dims, origin, spacing, fields in steps:
        for name in wanted:
            if name not in fields:
                fail(f"field {name} missing at t = {t} (have {sorted(fields)})")
        for name, values in fields.items():
            if name.endswith("_minus_fom"):
                model_field = name[:-len("_minus_fom")]
                component = next(c[:-len("_fom")] for c in fields if c.endswith("_fom") and
                                 model_field.startswith(c[:-len("fom")]))
                model = model_field[len(component) + 1:]
                ref = fields[component + "_fom"]
                err = np.max(np.abs(values - (fields[name[:-len("_minus_fom")]] - ref)))
                if err > 1e-12 * max(1.0, np.max(np.abs(ref))):
                    fail(f"{name} at t = {t} is not {model} - fom: off by {err}")
    if "--initial" in opts:
        t, dims, origin, spacing, fields = steps[0]
        nz, ny, nx = dims
        z, y, x = np.meshgrid(*(origin[d] + spacing[d] * np.arange(dims[d]) for d in range(3)), indexing="ij")
        scene, of = opts["--initial"], "_" + opts.get("--of", "fom")
        if scene.startswith("swe2d:"):
            beta = float(scene.split(":")[1])
            want, have = 1 + 0.5 * np.exp(-beta * (x ** 2 + y ** 2)), fields["chi" + of]
        else:
            want, have = math.sqrt(2) / np.cosh(x), np.hypot(fields["re_u" + of], fields["im_u" + of])
        err = np.max(np.abs(have - want.ravel()))
        if err > 1e-12:
            fail(f"the first state at the grid's coordinates is off the initial state by {err}")
    names = sorted(steps[0][4])
    print(f"xdmf ok: {len(steps)} times, {len(names)} fields ({', '.join(names)})")


if __name__ == "__main__":
    main()
