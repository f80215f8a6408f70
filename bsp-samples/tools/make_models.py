#!/usr/bin/env python3
"""Writes the binary sample models of bsp-samples/samples/models/samples/ (the text ones, .obj,
.mtl, .ase, .ply, .dae, .skin, are kept as written by hand):

  wedge.3ds  a ramp (3D Studio: main, editor, material, object, mesh, faces, UVs chunks)
  panel.lwo  a flat panel with two surfaces (LightWave LWO2: TAGS, LAYR, PNTS, POLS, PTAG, SURF)
  post.md3   a square post with two frames (frame 1 is taller), shader models/samples/post

Run it from anywhere; it rewrites the three files. The -bsp sample goldens depend on them.
"""
import os
import struct

OUT = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "samples", "models", "samples")


def chunk3ds(tag, payload):
    return struct.pack("<HI", tag, 6 + len(payload)) + payload


def write_3ds(path):
    # A ramp: 32 long (x), 24 wide (y), 16 high at its back; 3DS files are Z up.
    verts = [(0, 0, 0), (32, 0, 0), (32, 24, 0), (0, 24, 0), (32, 0, 16), (32, 24, 16)]
    faces = [(0, 1, 4), (3, 5, 2), (0, 4, 5), (0, 5, 3), (1, 2, 5), (1, 5, 4), (0, 3, 2), (0, 2, 1)]
    uvs = [(0, 0), (1, 0), (1, 1), (0, 1), (1, 0.5), (1, 0.5)]
    name = b"wedge\0"
    material = chunk3ds(0xAFFF, chunk3ds(0xA000, b"wedge\0") +
                        chunk3ds(0xA200, chunk3ds(0xA300, b"wedge.tga\0")))
    points = chunk3ds(0x4110, struct.pack("<H", len(verts)) + b"".join(struct.pack("<3f", *v) for v in verts))
    face_material = chunk3ds(0x4130, b"wedge\0" + struct.pack("<H", len(faces)) +
                             b"".join(struct.pack("<H", i) for i in range(len(faces))))
    face_list = chunk3ds(0x4120, struct.pack("<H", len(faces)) +
                         b"".join(struct.pack("<4H", a, b, c, 7) for a, b, c in faces) + face_material)
    texcoords = chunk3ds(0x4140, struct.pack("<H", len(uvs)) + b"".join(struct.pack("<2f", *t) for t in uvs))
    matrix = chunk3ds(0x4160, struct.pack("<12f", 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0))
    mesh = chunk3ds(0x4100, points + texcoords + matrix + face_list)
    editor = chunk3ds(0x3D3D, chunk3ds(0x3D3E, struct.pack("<I", 3)) + material + chunk3ds(0x4000, name + mesh))
    data = chunk3ds(0x4D4D, chunk3ds(0x0002, struct.pack("<I", 3)) + editor)
    with open(path, "wb") as f:
        f.write(data)


def iff(tag, payload):
    if len(payload) % 2:
        payload += b"\0"
    return tag + struct.pack(">I", len(payload)) + payload


def lwo_string(text):
    data = text.encode() + b"\0"
    return data + (b"\0" if len(data) % 2 else b"")


def write_lwo(path):
    # A 48 x 32 panel standing in the XY plane of LightWave (Y up), split into two surfaces.
    points = [(-24, 0, 0), (0, 0, 0), (24, 0, 0), (-24, 32, 0), (0, 32, 0), (24, 32, 0)]
    polygons = [(0, 3, 4, 1), (1, 4, 5, 2)]
    tags = lwo_string("textures/samples/trim") + lwo_string("panel")
    pnts = b"".join(struct.pack(">3f", *p) for p in points)
    pols = b"FACE" + b"".join(struct.pack(">H", len(p)) + b"".join(struct.pack(">H", i) for i in p) for p in polygons)
    ptag = b"SURF" + struct.pack(">HH", 0, 0) + struct.pack(">HH", 1, 1)
    colour = struct.pack(">H", 0x434F) + struct.pack(">H", 14) + struct.pack(">3f", 0.8, 0.8, 0.8) + struct.pack(">H", 0)
    surfaces = b"".join(iff(b"SURF", lwo_string(name) + lwo_string("") + b"COLR" + colour[2:])
                        for name in ("textures/samples/trim", "panel"))
    body = (b"LWO2" + iff(b"TAGS", tags) + iff(b"LAYR", struct.pack(">HH3f", 0, 0, 0, 0, 0) + lwo_string("panel")) +
            iff(b"PNTS", pnts) + iff(b"POLS", pols) + iff(b"PTAG", ptag) + surfaces)
    with open(path, "wb") as f:
        f.write(b"FORM" + struct.pack(">I", len(body)) + body)


def write_md3(path):
    # A 16 x 16 post, 48 high in frame 0 and 80 high in frame 1; MD3 units are 1/64.
    frames = [48, 80]
    base = [(-8, -8), (8, -8), (8, 8), (-8, 8)]
    verts, sts = [], []
    for height in frames:
        verts.append([(x, y, 0) for x, y in base] + [(x, y, height) for x, y in base])
    sts = [(i / 4.0, 1.0) for i in range(4)] + [(i / 4.0, 0.0) for i in range(4)]
    tris = []
    for i in range(4):
        j = (i + 1) % 4
        tris += [(i, j, j + 4), (i, j + 4, i + 4)]
    tris += [(4, 5, 6), (4, 6, 7)]
    normal = 0  # latitude 0, longitude 0: +Z (all corners alike)

    shader = struct.pack("<64si", b"models/samples/post.tga", 0)
    tri_data = b"".join(struct.pack("<3i", *t) for t in tris)
    st_data = b"".join(struct.pack("<2f", *s) for s in sts)
    xyz_data = b"".join(struct.pack("<3hH", x * 64, y * 64, z * 64, normal) for frame in verts for x, y, z in frame)
    header = 108
    ofs_shaders = header
    ofs_tris = ofs_shaders + len(shader)
    ofs_st = ofs_tris + len(tri_data)
    ofs_xyz = ofs_st + len(st_data)
    ofs_end = ofs_xyz + len(xyz_data)
    surface = struct.pack("<4s64s10i", b"IDP3", b"post", 0, len(frames), 1, 8, len(tris),
                          ofs_tris, ofs_shaders, ofs_st, ofs_xyz, ofs_end) + shader + tri_data + st_data + xyz_data
    frame_data = b"".join(struct.pack("<3f3f3ff16s", -8, -8, 0, 8, 8, h, 0, 0, 0, 12, b"frame") for h in frames)
    ofs_frames = 108
    ofs_surfaces = ofs_frames + len(frame_data)
    file_end = ofs_surfaces + len(surface)
    head = struct.pack("<4si64s9i", b"IDP3", 15, b"post.md3", 0, len(frames), 0, 1, 0,
                       ofs_frames, ofs_surfaces, ofs_surfaces, file_end)
    with open(path, "wb") as f:
        f.write(head + frame_data + surface)


if __name__ == "__main__":
    os.makedirs(OUT, exist_ok=True)
    write_3ds(os.path.join(OUT, "wedge.3ds"))
    write_lwo(os.path.join(OUT, "panel.lwo"))
    write_md3(os.path.join(OUT, "post.md3"))
