"""Opens an XDMF file of gphr with ParaView's XDMF Reader, as a user would, and checks what it shows.

usage: pvbatch paraview_read.py FILE.xdmf TIMES_DATASET ORIGIN_X,Y,Z SPACING_X,Y,Z

- the reader offers one time step per row of TIMES_DATASET, at those times, and every attribute
  the file names as a point array;
- the grid is an image of the grid's points with the given origin and spacing (x, y, z);
- at every time, every array holds exactly the numbers of the HDF5 row block the XDMF file names
  for it (read here with h5py: the reader must find the same hyperslab).
"""
import os
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np
from paraview import servermanager
from paraview.simple import XDMFReader


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


xdmf, times_dataset = sys.argv[1], sys.argv[2]
origin, spacing = ([float(x) for x in a.split(",")] for a in sys.argv[3:5])
here = os.path.dirname(os.path.abspath(xdmf))
# Where each field of each time is, from the XDMF text: (h5 path, dataset, row, first column, count).
where = []
for grid in ET.parse(xdmf).getroot().find("Domain/Grid").findall("Grid"):
    fields = {}
    for attr in grid.findall("Attribute"):
        sel, heavy = attr.find("DataItem").findall("DataItem")
        start = [int(x) for x in sel.text.split()][:2]
        count = [int(x) for x in sel.text.split()][4:]
        path, dataset = heavy.text.strip().rsplit(":", 1)
        fields[attr.get("Name")] = (os.path.join(here, path), dataset, start[0], start[1], count[1])
    where.append(fields)

reader = XDMFReader(FileNames=[xdmf])
reader.UpdatePipelineInformation()
times = list(reader.TimestepValues)
h5 = h5py.File(next(iter(where[0].values()))[0], "r")
expected = list(h5[times_dataset][...].ravel())
if times != expected:
    fail(f"ParaView offers the times {times}, the file holds {expected}")
names = sorted(reader.PointData.keys())
if names != sorted(where[0]):
    fail(f"ParaView offers the arrays {names}, the file names {sorted(where[0])}")
for j, t in enumerate(times):
    reader.UpdatePipeline(t)
    image = servermanager.Fetch(reader)
    if not np.allclose(image.GetOrigin(), origin, rtol=0, atol=1e-12) or \
            not np.allclose(image.GetSpacing(), spacing, rtol=0, atol=1e-12):
        fail(f"grid origin {image.GetOrigin()} spacing {image.GetSpacing()}, expected {origin} {spacing}")
    for name, (path, dataset, row, col, count) in where[j].items():
        array = image.GetPointData().GetArray(name)
        got = np.array([array.GetValue(i) for i in range(array.GetNumberOfValues())])
        want = h5py.File(path, "r")[dataset][row, col:col + count]
        if got.shape != want.shape or np.any(got != want):
            fail(f"{name} at t = {t}: ParaView shows {got.shape} values, not the file's {want.shape} of {dataset}")
print(f"ParaView's XDMF Reader: {len(times)} times, {len(names)} arrays, {image.GetNumberOfPoints()} points, "
      "every value as in the HDF5 file")
