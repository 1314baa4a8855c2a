"""Reads the .vtu files `tem run` writes (src/io/vtu_binary.hpp): VTK XML UnstructuredGrid with
every array in <AppendedData encoding="raw">, each compressed with zlib in VTK's blocks behind a
header of UInt64s (number of blocks, block size, size of a partial last block, compressed sizes).

Needs only numpy and Python's zlib. meshio reads these files too, but not one without cells (a
frame without contacts), and tools/figures.py does without meshio.
"""
import xml.etree.ElementTree as ET
import zlib

import numpy as np

TYPES = {"Float64": "<f8", "Int32": "<i4", "Int64": "<i8", "UInt8": "u1"}
OPENING = b'<AppendedData encoding="raw">'
CLOSING = b"\n</AppendedData>\n</VTKFile>\n"


def decode(data, offset, dtype):
    """The values of the array at `offset` of the appended data, and the offset just past it."""
    count, block_size, last = (int(v) for v in np.frombuffer(data, "<u8", 3, offset))
    sizes = [int(v) for v in np.frombuffer(data, "<u8", count, offset + 24)]
    position = offset + 8 * (3 + count)
    blocks = []
    for k, size in enumerate(sizes):
        block = zlib.decompress(data[position:position + size])
        expected = last if k == count - 1 and last else block_size
        if len(block) != expected:
            raise ValueError(f"block {k} at {offset}: {len(block)} bytes, header says {expected}")
        blocks.append(block)
        position += size
    return np.frombuffer(b"".join(blocks), dtype), position


def read_vtu(path):
    """(piece, arrays, time): the Piece element, {name: values} of the Piece's arrays (n x k
    for k components) and the FieldData TimeValue. Raises ValueError if the appended data does
    not hold exactly the declared arrays, one after another in some order."""
    with open(path, "rb") as f:
        raw = f.read()
    xml_end = raw.index(OPENING) + len(OPENING)
    if not raw.endswith(CLOSING) or raw[xml_end:xml_end + 2] != b"\n_":
        raise ValueError(f"{path}: not laid out as <AppendedData ...>\\n_DATA\\n</AppendedData>")
    root = ET.fromstring(raw[:xml_end] + CLOSING[1:])
    data = raw[xml_end + 2:len(raw) - len(CLOSING)]
    arrays = {}
    # The arrays tile the data with nothing between them, in the reverse of the XML's order
    # (vtu_binary.hpp says why); any order of offsets is read.
    declared = list(root.iter("DataArray"))
    position = 0
    for a in sorted(declared, key=lambda a: int(a.attrib["offset"])):
        if a.attrib["format"] != "appended" or int(a.attrib["offset"]) != position:
            raise ValueError(f"{path}: {a.attrib['Name']} is not at offset {position}")
        values, position = decode(data, position, TYPES[a.attrib["type"]])
        components = int(a.attrib.get("NumberOfComponents", "1"))
        arrays[a.attrib["Name"]] = values.reshape(-1, components) if components > 1 else values
    if position != len(data):
        raise ValueError(f"{path}: {len(data) - position} bytes after the last array")
    arrays = {a.attrib["Name"]: arrays[a.attrib["Name"]] for a in declared}  # in the XML's order
    time = arrays.pop("TimeValue")
    return root.find("UnstructuredGrid/Piece"), arrays, float(time[0])
