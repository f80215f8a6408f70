"""What the screenshot benches share: spawn points of a BSP, ioquake3 shots through
../shared/tools/q3-screenshot, and ImageMagick's PSNR of two pictures."""
import math
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHARED_TOOLS = os.path.join(os.path.dirname(ROOT), "shared", "tools")
SPAWNS = ("info_player_deathmatch", "info_player_start", "team_CTF_redspawn", "team_CTF_bluespawn")


def entities(bsp_path, prog):
    """The entity lump's entities as dicts (lump 0 of an IBSP)."""
    with open(bsp_path, "rb") as f:
        data = f.read()
    if data[:4] != b"IBSP":
        sys.exit("%s: %s is not an IBSP file" % (prog, bsp_path))
    offset = int.from_bytes(data[8:12], "little")
    length = int.from_bytes(data[12:16], "little")
    text = data[offset:offset + length].decode("latin-1")
    return [dict(re.findall(r'"([^"]*)"\s+"([^"]*)"', block)) for block in re.findall(r"\{([^{}]*)\}", text)]


def plain(value):
    """A number as q3-screenshot reads it: no exponent ("-7e-06" would be refused), no needless zeros."""
    text = ("%.4f" % value).rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def viewpoints(bsp_path, count, prog):
    """The first `count` spawn points (all of them for None), in q3-screenshot's -P form
    ("X Y Z YAW"), 9 units up as the game spawns a player."""
    views = []
    for e in entities(bsp_path, prog):
        if e.get("classname") not in SPAWNS or "origin" not in e:
            continue
        x, y, z = (float(v) for v in e["origin"].split()[:3])
        views.append(" ".join(plain(v) for v in (x, y, z + 9, float(e.get("angle", "0")))))
        if len(views) == count:
            break
    return views


def shoot(bsp, view, prefix, size, game_base, modes, prog, console=()):
    """Renders the modes from one viewpoint (PREFIX-ioq3-MODE.png); returns the r_debuglight reading
    ("amb / dir"). `console`: more ioquake3 console lines."""
    extra = [arg for line in console for arg in ("-x", "ioq3:" + line)]
    out = subprocess.run([os.path.join(SHARED_TOOLS, "q3-screenshot"), "-e", "ioq3", "-m", ",".join(modes),
                          "-S", size, "-b", game_base, "-P", view, "-o", prefix,
                          # The sky's clouds move with time: drawn flat, it compares what -light wrote.
                          "-x", "ioq3:set r_fastsky 1"] + extra + [bsp],
                         capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit("%s: q3-screenshot failed on %s (exit %d): %s" % (prog, bsp, out.returncode,
                                                                  (out.stdout + out.stderr).strip()[-400:]))
    light = re.search(r"amb:\s*(\d+)\s+dir:\s*(\d+)", out.stdout + out.stderr)
    return "%s / %s" % light.groups() if light else "-"


def psnr(a, b):
    """ImageMagick's PSNR of two pictures in dB (inf when identical), None when it gives none."""
    out = subprocess.run(["compare", "-metric", "PSNR", a, b, "null:"], capture_output=True, text=True)
    text = out.stderr.strip().split()[0] if out.stderr.strip() else ""
    try:
        return float(text)
    except ValueError:
        return float("inf") if text == "inf" else None


def magick(args):
    return subprocess.run(args, capture_output=True, text=True)


def stable_psnr(refs, ours, work, grow=1):
    """PSNR of ours against the reference over the pixels each tool's BSP renders the same way every
    time: animated shaders (tcMod scroll, animMap, rotating items) change between renders of one BSP
    and are left out. `refs`, `ours`: two or more renders of each BSP from one view, the first being
    the one judged. Moving pixels are grown by `grow` pixels, since a few renders catch a moving
    streak (star skies) only where it happened to be. Returns (PSNR, share of pixels left out)."""
    masks = []
    for shots in (refs, ours):
        for again in shots[1:]:
            masks.append(os.path.join(work, "mask%d.png" % len(masks)))
            magick(["compare", "-fuzz", "0", shots[0], again, "-compose", "src", "-highlight-color", "white",
                    "-lowlight-color", "black", masks[-1]])
    mask = os.path.join(work, "mask.png")
    magick(["convert"] + masks + ["-background", "black", "-compose", "lighten", "-flatten", "-colorspace", "gray"]
           + (["-morphology", "Dilate", "Square:%d" % grow] if grow > 0 else []) + [mask])
    moving = float(magick(["convert", mask, "-format", "%[fx:mean]", "info:"]).stdout or 0)
    merged = os.path.join(work, "merged.png")
    magick(["convert", ours[0], refs[0], mask, "-composite", merged])  # moving pixels taken from the reference
    text = magick(["compare", "-metric", "MSE", refs[0], merged, "null:"]).stderr
    mse = float(text[text.find("(") + 1:text.find(")")]) if "(" in text else 0.0
    return (10 * math.log10((1 - moving) / mse) if mse > 0 else float("inf")), moving
