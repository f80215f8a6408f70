"""What the bench scripts share: the OpenArena data cache, a fresh copy of a shipped map, and the
load average printed beside their figures."""
import os
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def data_cache():
    """The data cache folder, fetched first when missing (tools/fetch-openarena.sh prints it last)."""
    out = subprocess.run([os.path.join(ROOT, "tools", "fetch-openarena.sh")], check=True,
                         capture_output=True, text=True).stdout.strip().splitlines()
    return out[-1]


def find_file(cache, suffix):
    """The first file under <cache>/loose whose path ends with `suffix` (folders in walk order,
    names sorted), or None."""
    for dirpath, _, files in os.walk(os.path.join(cache, "loose")):
        for f in sorted(files):
            path = os.path.join(dirpath, f)
            if path.endswith(suffix):
                return path
    return None


def stage_map(cache, work, name, prog):
    """A fresh copy of the shipped BSP and its .map source in work/baseoa/maps/ (work is emptied
    first); returns the BSP's path. An unknown map ends the program with a message naming `prog`."""
    shutil.rmtree(work, ignore_errors=True)
    maps = os.path.join(work, "baseoa", "maps")
    os.makedirs(maps)
    bsp = find_file(cache, os.sep + "maps" + os.sep + name + ".bsp")
    if bsp is None:
        sys.exit("%s: no map named %s in %s" % (prog, name, cache))
    shutil.copyfile(bsp, os.path.join(maps, name + ".bsp"))
    source = find_file(cache, os.sep + "maps" + os.sep + name + ".map")
    if source:
        shutil.copyfile(source, os.path.join(maps, name + ".map"))
    return os.path.join(maps, name + ".bsp")


def load_average():
    try:
        with open("/proc/loadavg") as f:
            return " ".join(f.read().split()[:3])
    except OSError:
        return "?"
