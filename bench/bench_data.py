"""What the bench scripts share: the OpenArena data cache, a fresh copy of a shipped map, and the
load average printed beside their figures."""
import functools
import os
import shutil
import subprocess
import sys
import tempfile
import time
import zipfile

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


def _fnv1a64(h, data):
    for b in data:
        h = ((h ^ b) * 0x100000001b3) & 0xFFFFFFFFFFFFFFFF
    return h


def fnv1a64(path):
    with open(path, "rb") as f:
        return "%016x" % _fnv1a64(0xcbf29ce484222325, f.read())


@functools.lru_cache(maxsize=None)
def reference_hash(reference):
    """FNV-1a 64 over the reference's folder (each regular file's name, a NUL, its bytes, in name
    order): its identity in cache keys, whatever its timestamps (tests/conformance computes the same)."""
    folder = os.path.dirname(os.path.abspath(reference))
    h = 0xcbf29ce484222325
    for name in sorted(os.listdir(folder)):
        path = os.path.join(folder, name)
        if not os.path.isfile(path):
            continue
        with open(path, "rb") as f:
            h = _fnv1a64(h, name.encode() + b"\0" + f.read())
    return "%016x" % h


def fresh_key(reference, map_source):
    """The cache folder name of a map compiled by the reference: <map>-<reference hash>-<.map hash>."""
    name = os.path.splitext(os.path.basename(map_source))[0]
    return "%s-%s-%s" % (name, reference_hash(reference), fnv1a64(map_source))


def compile_for_light(common, work, name):
    """-bsp -meta of work/maps/NAME.map, then -vis -fast, by the tool `common` starts (binary and base
    path options), logs in work/; only the inputs of -light stay in maps/. None when both ran, else
    (step, exit code) of the one that failed."""
    maps = os.path.join(work, "maps")
    for step, args, target, log in (("-bsp", ["-meta"], name + ".map", "bsp.log"),
                                     ("-vis", ["-fast"], name + ".bsp", "vis.log")):
        with open(os.path.join(work, log), "w") as out:
            code = subprocess.call(common + [step] + args + [os.path.join(maps, target)], cwd=work,
                                   stdout=out, stderr=subprocess.STDOUT)
        if code != 0:
            return step, code
    for f in os.listdir(maps):
        if os.path.splitext(f)[1] not in (".bsp", ".srf", ".map"):
            os.remove(os.path.join(maps, f))
    return None


def fresh_compile(reference, game_base, cache, map_source, prog):
    """The reference's -bsp -meta and -vis -fast of a .map, cached under <cache>/conformance/fresh/
    (keyed by fresh_key, the same cache the conformance tests use): the folder holding maps/NAME.bsp, .srf and .map. A failure ends the
    program with a message naming `prog`."""
    name = os.path.splitext(os.path.basename(map_source))[0]
    key = fresh_key(reference, map_source)
    root = os.path.join(cache, "conformance", "fresh")
    final = os.path.join(root, key)
    if os.path.exists(os.path.join(final, "maps", name + ".bsp")):
        return final
    os.makedirs(root, exist_ok=True)
    work = tempfile.mkdtemp(prefix=".tmp-%s-" % name, dir=root)
    maps = os.path.join(work, "maps")
    os.makedirs(maps)
    shutil.copyfile(map_source, os.path.join(maps, name + ".map"))
    common = [reference, "-game", "quake3", "-fs_basepath", game_base, "-fs_basegame", "baseoa", "-threads", "2"]
    failed = compile_for_light(common, work, name)
    if failed:
        shutil.rmtree(work, ignore_errors=True)
        sys.exit("%s: reference %s on %s failed (exit %d)" % (prog, failed[0], map_source, failed[1]))
    try:
        os.rename(work, final)
    except OSError:  # another run put its compile there first
        shutil.rmtree(work, ignore_errors=True)
    return final


def stage(fresh, dest, name):
    """A copy of the fresh compile's files in dest/maps/ (dest emptied first); the BSP's path."""
    shutil.rmtree(dest, ignore_errors=True)
    os.makedirs(os.path.join(dest, "maps"))
    for ext in (".bsp", ".srf", ".map"):
        src = os.path.join(fresh, "maps", name + ext)
        if os.path.exists(src):
            shutil.copyfile(src, os.path.join(dest, "maps", name + ext))
    return os.path.join(dest, "maps", name + ".bsp")


def measure(cmd, cwd=None):
    """Runs one command (in `cwd`); wall time from the clock, user time and peak RSS from wait4. A
    failure ends the program with the end of its output."""
    with tempfile.TemporaryFile() as output:
        start = time.monotonic()
        proc = subprocess.Popen(cmd, cwd=cwd, stdout=output, stderr=subprocess.STDOUT)
        _, status, usage = os.wait4(proc.pid, 0)
        wall = time.monotonic() - start
        if os.waitstatus_to_exitcode(status) != 0:
            output.seek(0)
            tail = output.read()[-3000:].decode(errors="replace")
            sys.exit("%s: %s failed:\n%s" % (os.path.basename(sys.argv[0]), " ".join(cmd), tail))
    return {"wall": wall, "user": usage.ru_utime, "peak_rss_mb": usage.ru_maxrss / 1024.0}


def shader_list_base(base, game, work):
    """A base path holding <game>/scripts/shaderlist.txt naming every .shader of the game folder,
    loose or in its pk3s, as the reference's wrapper writes it."""
    names = set()
    folder = os.path.join(base, game)
    scripts = os.path.join(folder, "scripts")
    if os.path.isdir(scripts):
        names.update(f[:-7] for f in os.listdir(scripts) if f.endswith(".shader"))
    for pk3 in sorted(f for f in os.listdir(folder) if f.endswith(".pk3")):
        with zipfile.ZipFile(os.path.join(folder, pk3)) as z:
            for entry in z.namelist():
                if entry.startswith("scripts/") and entry.endswith(".shader") and entry.count("/") == 1:
                    names.add(entry[len("scripts/"):-7])
    listed = os.path.join(work, game, "scripts")
    os.makedirs(listed)
    with open(os.path.join(listed, "shaderlist.txt"), "w") as f:
        f.write("".join(n + "\n" for n in sorted(names)))
    return work
