"""What the -vis benches share: the reference's -bsp -meta of a map with its .prt, timed -vis runs,
the reference's full vis kept beside them, and the BSP's lumps (the visibility lump above all)."""
import json
import os
import shutil
import struct
import subprocess
import sys
import tempfile

from bench_data import ROOT, find_file, fresh_key, load_average, measure

PROG = os.path.basename(sys.argv[0])
VISIBILITY = 16  # lump index of the PVS in an IBSP v46 file


DEFAULT_REFERENCE = os.path.join(os.path.dirname(ROOT), "shared", "tools", "q3map2-reference", "q3map2")


def reference_args(reference, cache, threads):
    return [reference, "-game", "quake3", "-fs_basepath", os.path.join(cache, "openarena"),
            "-fs_basegame", "baseoa", "-threads", str(threads)]


def vis_inputs(reference, cache, name, threads):
    """The cached reference -bsp -meta of map `name`: (bsp, prt), compiled when missing."""
    source = find_file(cache, os.sep + "maps" + os.sep + name + ".map")
    if source is None:
        sys.exit(PROG + ": no .map source named %s in %s" % (name, cache))
    folder = os.path.join(cache, "vis", fresh_key(reference, source))
    bsp, prt = os.path.join(folder, name + ".bsp"), os.path.join(folder, name + ".prt")
    if os.path.exists(prt):
        return bsp, prt
    work = tempfile.mkdtemp(prefix=".tmp-%s-" % name, dir=os.path.join(cache, "vis") if os.path.isdir(
        os.path.join(cache, "vis")) else None)
    os.makedirs(os.path.join(work, "maps"))
    shutil.copyfile(source, os.path.join(work, "maps", name + ".map"))
    done = subprocess.run(reference_args(reference, cache, threads) + ["-bsp", "-meta", "maps/%s.map" % name],
                          cwd=work, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(PROG + ": reference -bsp -meta failed on %s:\n%s" % (name, done.stdout[-2000:]))
    for ext in (".bsp", ".prt"):
        os.replace(os.path.join(work, "maps", name + ext), os.path.join(work, name + ext))
    shutil.rmtree(os.path.join(work, "maps"))
    os.makedirs(os.path.dirname(folder), exist_ok=True)
    try:
        os.rename(work, folder)
    except OSError:
        shutil.rmtree(work)  # another run put its compile there first
    return bsp, prt


def reference_vis(args, cache, name, options, bsp, prt, work):
    """The reference's -vis figures on (bsp, prt), from the cache next to them when measured before."""
    folder = os.path.dirname(bsp)
    tag = "".join(options).replace(" ", "_") or "full"
    record = os.path.join(folder, "%s.%s.threads%d.json" % (name, tag, args.threads))
    # At 2 threads the BSP takes the name tests/vis gives the same run (vis_reference.h).
    kept = {"full": name + ".full.bsp", "-fast": name + ".fast.bsp"}.get(tag, name + tag + ".bsp")
    if args.threads != 2:
        kept = "%s.%s.threads%d.bsp" % (name, tag, args.threads)
    if os.path.exists(record) and not args.fresh_reference:
        with open(record) as f:
            result = json.load(f)
        result["cached"] = record
        return result
    os.makedirs(os.path.join(work, "q3map2"))
    copy = os.path.join(work, "q3map2", name + ".bsp")
    shutil.copyfile(bsp, copy)
    shutil.copyfile(prt, os.path.join(work, "q3map2", name + ".prt"))
    result = measure(reference_args(args.reference, cache, args.threads) + ["-vis"] + options + [copy])
    result["visible"] = visible_share(copy)
    result["load_average"] = load_average()
    if not os.path.exists(os.path.join(folder, kept)):
        shutil.copyfile(copy, os.path.join(folder, kept + ".tmp"))
        os.replace(os.path.join(folder, kept + ".tmp"), os.path.join(folder, kept))
    with open(record + ".tmp", "w") as f:
        json.dump(result, f, indent=1)
    os.replace(record + ".tmp", record)
    return result


def visible_share(bsp):
    """Mean share of clusters each cluster's row marks visible (lump 16)."""
    with open(bsp, "rb") as f:
        data = f.read()
    if len(lump(data, VISIBILITY)) < 8:
        return float("nan")
    clusters, _, rows = pvs_rows(data)
    return sum(bin(b).count("1") for b in rows) / float(clusters * clusters) if clusters else 0.0


def lump(data, index):
    """Lump `index` of an IBSP file's bytes."""
    offset, length = struct.unpack_from("<ii", data, 8 + 8 * index)
    return data[offset:offset + length]


def with_lump(data, index, payload):
    """The file's bytes with lump `index` replaced by `payload` of the same length (a vis lump of the
    same cluster count always is)."""
    offset, length = struct.unpack_from("<ii", data, 8 + 8 * index)
    if length != len(payload):
        sys.exit("%s: lump %d is %d bytes, its replacement %d" % (PROG, index, length, len(payload)))
    return data[:offset] + payload + data[offset + length:]


def pvs_rows(data):
    """(clusters, bytes per row, rows as bytes) of an IBSP file's visibility lump."""
    vis = lump(data, VISIBILITY)
    clusters, row_bytes = struct.unpack_from("<ii", vis)
    return clusters, row_bytes, vis[8:8 + clusters * row_bytes]
