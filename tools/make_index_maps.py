#!/usr/bin/env python3
"""Writes the terrain samples' 4x4 index maps into bsp-samples/samples/maps/.

terrain_indexmap.tga: 24-bit, bottom-left origin; red 0, 128 and 255 give layers 0, 1 and 2 of 3.
terrain_indexmap.pcx: version 5 RLE, 8 bits; palette indexes are the layers (one 5, past the last).
terrain_indexmap.bmp: 8 bits, bottom-up, the same indexes as the PCX.
Rows are listed top (the largest y of the entity) to bottom.
"""
import pathlib
import struct

LAYERS = [[0, 0, 1, 2],
          [0, 1, 1, 2],
          [0, 1, 1, 2],
          [0, 0, 2, 2]]
INDEXES = [[0, 0, 1, 2],
           [0, 1, 1, 2],
           [0, 1, 1, 5],
           [0, 0, 2, 2]]
RED = {0: 0, 1: 128, 2: 255}


def tga():
    header = struct.pack('<BBBHHBHHHHBB', 0, 0, 2, 0, 0, 0, 0, 0, 4, 4, 24, 0)
    pixels = b''.join(bytes([RED[v] // 2, RED[v] // 3, RED[v]]) for row in reversed(LAYERS) for v in row)
    return header + pixels


def pcx():
    header = bytearray(128)
    header[0:4] = bytes([0x0a, 5, 1, 8])
    struct.pack_into('<HHHHHH', header, 4, 0, 0, 3, 3, 72, 72)
    header[65] = 1
    struct.pack_into('<HH', header, 66, 4, 1)
    data = bytearray()
    for row in INDEXES:
        i = 0
        while i < len(row):
            j = i
            while j < len(row) and row[j] == row[i]:
                j += 1
            if j - i > 1 or row[i] >= 0xc0:
                data += bytes([0xc0 | (j - i), row[i]])
            else:
                data.append(row[i])
            i = j
    return bytes(header) + bytes(data) + b'\x0c' + bytes(768)


def bmp():
    pixels = b''.join(bytes(row) for row in reversed(INDEXES))
    offset = 14 + 40 + 1024
    return (b'BM' + struct.pack('<IHHI', offset + len(pixels), 0, 0, offset) +
            struct.pack('<IiiHHIIiiII', 40, 4, 4, 1, 8, 0, len(pixels), 2835, 2835, 256, 0) + bytes(1024) + pixels)


def main():
    maps = pathlib.Path(__file__).resolve().parent.parent / 'bsp-samples' / 'samples' / 'maps'
    for ext, make in (('tga', tga), ('pcx', pcx), ('bmp', bmp)):
        (maps / f'terrain_indexmap.{ext}').write_bytes(make())


if __name__ == '__main__':
    main()
