#!/usr/bin/python3
"""Derives damaged reduced-model files from a good one, as a hostile-but-honest user editing it with
h5py would: truncations, deleted and resized datasets, out-of-range and non-finite values, changed
attribute types, and flipped bits inside the datasets' stored bytes and the object headers. Writes OUT/<case>.h5 and
OUT/cases.txt, one line "<case> <expected exit code>": 2 for a damaged file, 0 for an edit that
keeps the model (a string attribute rewritten as a variable-length string, as other writers make).

usage: fuzz_model_files.py GOOD.h5 OUT_DIR
"""
import os
import shutil
import sys

import h5py
import numpy as np

good, out = sys.argv[1], sys.argv[2]
os.makedirs(out, exist_ok=True)
cases = []


def derive(name, edit, expect=2):
    path = os.path.join(out, name + ".h5")
    shutil.copy(good, path)
    if edit is not None:
        edit(path)
    cases.append((name, expect))


with h5py.File(good, "r") as f:
    models = f.attrs["models"].decode() if isinstance(f.attrs["models"], bytes) else f.attrs["models"]
    key = models.split(";")[0]                      # method/k<k>/m<m>
    method, kk, mm = key.split("/")
    gm = f"/{kk}/{method}/{mm}"
    gk = f"/{kk}"
    datasets = [gm + "/rows", gm + "/weights", gm + "/stencil_offsets", gm + "/stencil_gids", gm + "/basis_rows",
                gk + "/interpolation_values", gk + "/constant_values", gk + "/reference_gids", gk + "/probe_rows"]
    offsets = {d: f[d].id.get_offset() for d in datasets}
    sizes = {d: f[d].id.get_storage_size() for d in datasets}
    # object headers (attributes, links, layouts): address and size of the root's and a model's
    headers = {name: (info.addr, info.hdr.space.total)
               for name, info in (("root", h5py.h5o.get_info(f.id)), ("model", h5py.h5o.get_info(f[gm].id)))}
size = os.path.getsize(good)


def truncate(frac):
    def edit(path):
        with open(path, "r+b") as g:
            g.truncate(int(size * frac))
    return edit


def flip(dataset):
    def edit(path):  # one bit of a stored value: the value stays finite, only the checksum sees it
        with open(path, "r+b") as g:
            at = offsets[dataset] + (sizes[dataset] // 16) * 8 + 1
            g.seek(at)
            b = g.read(1)[0]
            g.seek(at)
            g.write(bytes([b ^ 0x08]))
    return edit


def flip_header(obj, fraction):
    def edit(path):  # one bit inside an object header: the 1.8 format's checksum must refuse it
        at, size = headers[obj]
        at += 16 + int((size - 16) * fraction)
        with open(path, "r+b") as g:
            g.seek(at)
            b = g.read(1)[0]
            g.seek(at)
            g.write(bytes([b ^ 0x10]))
    return edit


def with_file(fn):
    def edit(path):
        with h5py.File(path, "r+") as g:
            fn(g)
    return edit


def set_entry(dataset, index, value):
    def fn(g):
        a = g[dataset][...]
        a.flat[index] = value
        g[dataset][...] = a
    return with_file(fn)


def resize(dataset, extra):
    def fn(g):
        a = g[dataset][...]
        a = np.concatenate([a, a[-1:]]) if extra > 0 else a[:-1]
        attrs = dict(g[dataset].attrs)
        del g[dataset]
        g[dataset] = a
        for k, v in attrs.items():
            g[dataset].attrs[k] = v
    return with_file(fn)


def set_attr(obj, name, value):
    def fn(g):
        if value is None:
            if name in g[obj].attrs:
                del g[obj].attrs[name]
        else:
            g[obj].attrs[name] = value
    return with_file(fn)


def vlen(obj, name):  # the same string, stored as a variable-length string
    def fn(g):
        if name not in g[obj].attrs:  # a file of a gphr without it (the fuzz run against older builds)
            return
        v = g[obj].attrs[name]
        v = v.decode() if isinstance(v, bytes) else v
        del g[obj].attrs[name]
        g[obj].attrs.create(name, v, dtype=h5py.string_dtype())
    return with_file(fn)


for frac in (0.1, 0.5, 0.9, 0.99):
    derive(f"truncated_{int(frac * 100)}", truncate(frac))
for d in datasets:
    tag = d.strip("/").replace("/", "_")
    derive("flipped_" + tag, flip(d))
    derive("deleted_" + tag, with_file(lambda g, d=d: g.__delitem__(d)))
    derive("grown_" + tag, resize(d, 1))
for d in (gm + "/weights", gm + "/basis_rows", gk + "/interpolation_values", gk + "/constant_values", gk + "/probe_rows"):
    tag = d.strip("/").replace("/", "_")
    derive("nan_" + tag, set_entry(d, 0, np.nan))
    derive("inf_" + tag, set_entry(d, 0, np.inf))
for i in range(8):  # the earliest file format (no checksums) took 314 of 1,446 such flips silently
    derive(f"header_root_{i}", flip_header("root", (i + 0.5) / 8))
derive("header_model", flip_header("model", 0.5))
def filtered(dataset):  # the same values through h5py's LZF filter, a plugin this libhdf5 lacks
    def fn(g):
        a = g[dataset][...]
        attrs = dict(g[dataset].attrs)
        del g[dataset]
        g.create_dataset(dataset, data=a, compression="lzf", chunks=True)
        for k, v in attrs.items():
            g[dataset].attrs[k] = v
    return with_file(fn)


derive("lzf_weights", filtered(gm + "/weights"))
derive("offsets_1000", set_entry(gm + "/stencil_offsets", 1, 1000))
derive("offsets_negative", set_entry(gm + "/stencil_offsets", 1, -1))
derive("offsets_fraction", set_entry(gm + "/stencil_offsets", 1, 0.5))
derive("offsets_decreasing", set_entry(gm + "/stencil_offsets", 2, 0))
derive("rows_negative", set_entry(gm + "/rows", 0, -3))
derive("rows_huge", set_entry(gm + "/rows", 0, 1e18))
derive("rows_repeated", set_entry(gm + "/rows", 1, -1))  # replaced below by a repeat of entry 0
derive("gids_huge", set_entry(gm + "/stencil_gids", 0, 1e17))
derive("schema_as_string", set_attr("/", "schema_version", "3"))
derive("schema_old", set_attr("/", "schema_version", 2.0))
derive("scene_as_number", set_attr("/", "scene", 5))
derive("models_as_number", set_attr("/", "models", 1.5))
derive("models_repeated", set_attr("/", "models", key + ";" + key))
derive("models_bad_key", set_attr("/", "models", f"{method}/kx/{mm}"))
derive("models_missing_group", set_attr("/", "models", f"{method}/{kk}/m999"))


def as_method(name):  # the model's group copied under another method's name, the list naming it
    def edit(g):
        g.copy(gm, f"/{kk}/{name}/{mm}")
        g.attrs["models"] = f"{name}/{kk}/{mm}"
    return edit


derive("models_rom_method", with_file(as_method("rom")))  # a method no model file holds
derive("models_unknown_method", with_file(as_method("pod-deim")))
derive("checksum_deleted", set_attr("/", "checksum", None))
derive("checksum_changed", set_attr("/", "checksum", "fnv1a64:0000000000000000"))
derive("time_as_string", set_attr("/", "time", "1 0.01"))
derive("time_dt_zero", set_attr("/", "time", np.array([1.0, 0.0])))
derive("box_reversed", set_attr("/", "box_lower", np.array([2.0])))
derive("enters_out_of_range", set_attr("/", "parameter_enters", np.array([99.0])))
derive("nodes_huge", set_attr(gk + "/constant_values", "nodes_per_parameter", np.array([1.0, 1e9])))
derive("degree_fraction", set_attr("/", "polynomial_degree", 2.5))
derive("scene_vlen_string", vlen("/", "scene"), expect=0)
derive("checksum_vlen_string", vlen("/", "checksum"), expect=0)
derive("unchanged", None, expect=0)

# rows_repeated: entry 1 := entry 0
with h5py.File(os.path.join(out, "rows_repeated.h5"), "r+") as g:
    a = g[gm + "/rows"][...]
    a[1] = a[0]
    g[gm + "/rows"][...] = a

with open(os.path.join(out, "cases.txt"), "w") as c:
    for name, expect in cases:
        c.write(f"{name} {expect}\n")
print(f"{len(cases)} files derived from {good} ({key})")
