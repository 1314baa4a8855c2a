#!/usr/bin/python3
"""Checks `tem run`'s ParaView output with a real reader (Debian's meshio) against the CSV files
of the same run and against `tem info --json`.

usage: check_paraview.py TEM_BINARY SCENE WORK_DIR

The scene must set output.paraview. For every frame listed in tem.pvd it checks that
- the frame's time is a row time of bodies.csv and energy.csv, in the same order, and both
  files (part 0 bodies, part 1 contacts) exist;
- each body's surface is the same rigid shape in every frame: its points mapped back into the
  body frame with the pose of bodies.csv (x, quaternion) coincide with frame 0's;
- each body's surface encloses the volume of `tem info --json` and its centroid is the centre
  of mass x of bodies.csv (divergence theorem over the triangles); at time 0 its inertia
  tensor is info's (which also catches a block turned about its own centroid);
- the velocity field is v + w x (p - x) and the angular velocity field is w, from bodies.csv;
- the contact file has as many points as energy.csv's contacts, unit normals, the deepest
  depth of energy.csv, force = fn * normal, and body_a, body_b, wall that agree;
- both files are binary as src/io/vtu_binary.hpp says (appended raw data, zlib blocks), their
  TimeValue is the frame's time, and tools/tem_vtu.py, a second reader, decodes every array
  meshio reads to the same bits.
It exits non-zero, printing every failure, if anything is off.
"""
import csv
import json
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

import meshio
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
import tem_vtu  # noqa: E402

RELATIVE = 1e-9  # round-off allowance, relative to the body's size or speed
failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
    return condition


def rotation(qw, qx, qy, qz):
    """Rotation matrix (body to world) of a unit quaternion [w, x, y, z]."""
    return np.array([
        [1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qw * qz), 2 * (qx * qz + qw * qy)],
        [2 * (qx * qy + qw * qz), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qw * qx)],
        [2 * (qx * qz - qw * qy), 2 * (qy * qz + qw * qx), 1 - 2 * (qx * qx + qy * qy)],
    ])


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def volume_and_centroid(points, triangles):
    """Volume and centroid of the solid a closed, outward-oriented triangle surface bounds:
    the signed tetrahedra (origin, triangle) summed (divergence theorem)."""
    a, b, c = (points[triangles[:, k]] for k in range(3))
    volumes = np.einsum("ij,ij->i", a, np.cross(b, c)) / 6.0
    volume = volumes.sum()
    return volume, (volumes[:, None] * (a + b + c) / 4.0).sum(axis=0) / volume


CONTACT_ARRAYS = ["normal", "depth", "fn", "ft", "force", "body_a", "body_b", "wall", "Points",
                  "connectivity", "offsets", "types"]


def read_binary(path, time):
    """The Piece and arrays of a frame file as tools/tem_vtu.py decodes them, with the root's
    attributes and TimeValue checked."""
    with open(path, "rb") as f:
        head = f.read(300).decode("latin-1")
    for attribute in ('byte_order="LittleEndian"', 'header_type="UInt64"',
                      'compressor="vtkZLibDataCompressor"'):
        check(attribute in head.split("\n")[1], f"{path}: no {attribute}")
    piece, arrays, time_value = tem_vtu.read_vtu(path)
    check(time_value == float(time), f"{path}: TimeValue {time_value!r} != tem.pvd's {time}")
    return piece, arrays


def same_as_meshio(path, mesh, arrays, cell_type):
    """meshio's arrays bit for bit equal to tem_vtu's (the two readers agree)."""
    mine = {"Points": arrays["Points"], "connectivity": arrays["connectivity"]}
    theirs = {"Points": mesh.points, "connectivity": mesh.cells_dict[cell_type].reshape(-1)}
    theirs.update(mesh.point_data)
    theirs.update({name: data[0] for name, data in mesh.cell_data.items()})
    for name in theirs:
        mine.setdefault(name, arrays.get(name))
        check(mine[name] is not None and mine[name].dtype == theirs[name].dtype and
              np.array_equal(mine[name].view(np.uint8), theirs[name].view(np.uint8)),
              f"{path}: {name} read differently by meshio and tem_vtu")


def contact_count(path, piece, arrays):
    """The number of points of a contacts file. meshio 7.0 cannot read a file without cells (it
    indexes the first cell type), so a frame without contacts is checked here: a valid VTK file
    with 0 points, 0 cells and every array present and empty."""
    points, cells = int(piece.attrib["NumberOfPoints"]), int(piece.attrib["NumberOfCells"])
    check(points == cells, f"{path}: {points} points but {cells} cells")
    if points == 0:
        check(sorted(arrays) == sorted(CONTACT_ARRAYS), f"{path}: arrays {sorted(arrays)}")
        check(all(len(v) == 0 for v in arrays.values()), f"{path}: values in an empty frame")
    return points


def inertia(points, triangles, centre, density):
    """Inertia tensor about `centre` of the solid a closed triangle surface bounds: per signed
    tetrahedron (centre, triangle), S = V/20 (sum p p^T + (sum p)(sum p)^T) over its corners
    relative to the centre, and I = density (trace(S) 1 - S)."""
    a, b, c = (points[triangles[:, k]] - centre for k in range(3))
    volumes = np.einsum("ij,ij->i", a, np.cross(b, c)) / 6.0
    total = a + b + c
    outer = lambda u, w: np.einsum("ni,nj->nij", u, w)  # noqa: E731
    second = (volumes[:, None, None] / 20.0 *
              (outer(a, a) + outer(b, b) + outer(c, c) + outer(total, total))).sum(axis=0)
    return density * (np.trace(second) * np.eye(3) - second)


def main():
    tem, scene, work = sys.argv[1:4]
    out = os.path.join(work, "run")
    shutil.rmtree(out, ignore_errors=True)
    subprocess.run([tem, "run", scene, "--out", out], check=True, stdout=subprocess.DEVNULL)
    info = json.loads(subprocess.run([tem, "info", scene, "--json"], check=True,
                                     capture_output=True, text=True).stdout)
    names = [b["name"] for b in info["bodies"]]
    volumes = [b["volume"] for b in info["bodies"]]
    densities = [b["mass"] / b["volume"] for b in info["bodies"]]
    inertias = [np.array(b["inertia"]) for b in info["bodies"]]

    # bodies.csv: per time, per body (in the order of the scene, which body_id follows).
    rows = read_csv(os.path.join(out, "bodies.csv"))
    times = []
    poses = {}
    for r in rows:
        if not times or times[-1] != r["time"]:
            times.append(r["time"])
        poses.setdefault(r["time"], []).append(r)
    for t in times:
        check([r["body"] for r in poses[t]] == names, f"t={t}: bodies.csv body order != info")
    energy = read_csv(os.path.join(out, "energy.csv"))
    check([e["time"] for e in energy] == times, "energy.csv and bodies.csv times differ")

    # tem.pvd: one bodies and one contacts file per time, in order.
    collection = ET.parse(os.path.join(out, "tem.pvd")).getroot().find("Collection")
    frames = {}
    order = []
    for d in collection.findall("DataSet"):
        t = d.attrib["timestep"]
        if t not in frames:
            order.append(t)
        frames.setdefault(t, {})[d.attrib["part"]] = os.path.join(out, d.attrib["file"])
    check(order == times, f"tem.pvd timesteps {order} != bodies.csv times {times}")
    check(not os.path.exists(os.path.join(out, "tem.pvd.tmp")), "tem.pvd.tmp left behind")

    reference = None  # frame 0's body-frame points, per point
    contact_frames = 0
    for t, e in zip(order, energy):
        parts = frames[t]
        if not check(sorted(parts) == ["0", "1"], f"t={t}: parts {sorted(parts)} != 0, 1"):
            continue
        if not all(check(os.path.isfile(p), f"{p}: listed in tem.pvd, missing") for p in
                   parts.values()):
            continue

        # Bodies.
        mesh = meshio.read(parts["0"])
        same_as_meshio(parts["0"], mesh, read_binary(parts["0"], t)[1], "triangle")
        points = mesh.points
        triangles = mesh.cells_dict["triangle"]
        body_id = mesh.cell_data_dict["body_id"]["triangle"]
        block_id = mesh.cell_data_dict["block_id"]["triangle"]
        check(list(np.unique(body_id)) == list(range(len(names))), f"t={t}: body ids")
        check(np.all(np.diff(block_id) >= 0) and np.all(np.diff(body_id) >= 0),
              f"t={t}: cells not in body, block order")
        body_of_point = np.full(len(points), -1)
        for k in range(3):
            body_of_point[triangles[:, k]] = body_id
        check(np.all(body_of_point >= 0), f"t={t}: a point in no triangle")
        in_body = np.zeros_like(points)
        for b, r in enumerate(poses[t]):
            x = np.array([float(r[k]) for k in ("x", "y", "z")])
            q = [float(r[k]) for k in ("qw", "qx", "qy", "qz")]
            v = np.array([float(r[k]) for k in ("vx", "vy", "vz")])
            w = np.array([float(r[k]) for k in ("wx", "wy", "wz")])
            mine = body_of_point == b
            p = points[mine]
            size = np.max(np.linalg.norm(p - x, axis=1))
            in_body[mine] = (p - x) @ rotation(*q)  # R^T (p - x), row by row

            volume, centroid = volume_and_centroid(points, triangles[body_id == b])
            check(abs(volume - volumes[b]) <= RELATIVE * volumes[b],
                  f"t={t} {names[b]}: volume {volume!r} != info {volumes[b]!r}")
            check(np.linalg.norm(centroid - x) <= RELATIVE * size,
                  f"t={t} {names[b]}: centroid {centroid} != x {x}")

            if reference is None:  # the initial pose, at which info gives the inertia
                tensor = inertia(points, triangles[body_id == b], x, densities[b])
                scale = np.max(np.abs(inertias[b]))
                check(np.max(np.abs(tensor - inertias[b])) <= RELATIVE * scale,
                      f"{names[b]}: inertia of the surface {tensor.tolist()} != info "
                      f"{inertias[b].tolist()}")

            expected = v + np.cross(w, p - x)
            error = np.max(np.linalg.norm(mesh.point_data["velocity"][mine] - expected, axis=1))
            speed = np.linalg.norm(v) + np.linalg.norm(w) * size
            check(error <= RELATIVE * speed + 1e-300,
                  f"t={t} {names[b]}: velocity off by {error!r} (speed {speed!r})")
            check(np.array_equal(mesh.point_data["angular_velocity"][mine],
                                 np.tile(w, (p.shape[0], 1))),
                  f"t={t} {names[b]}: angular_velocity != w of bodies.csv")
            if reference is not None:
                shift = np.max(np.linalg.norm(in_body[mine] - reference[mine], axis=1))
                check(shift <= RELATIVE * size,
                      f"t={t} {names[b]}: body-frame points moved by {shift!r} since frame 0")
        if reference is None:
            reference = in_body

        # Contacts.
        n = int(e["contacts"])
        contact_frames += n > 0
        count = contact_count(parts["1"], *read_binary(parts["1"], t))
        check(count == n, f"t={t}: {count} contact points, energy.csv says {n}")
        if n == 0 or count != n:
            continue
        contacts = meshio.read(parts["1"])
        same_as_meshio(parts["1"], contacts, read_binary(parts["1"], t)[1], "vertex")
        check(len(contacts.points) == n, f"t={t}: meshio reads {len(contacts.points)} points")
        data = contacts.point_data
        normal = data["normal"]
        check(np.all(np.abs(np.linalg.norm(normal, axis=1) - 1) <= 1e-12),
              f"t={t}: contact normals not unit")
        check(float(np.max(data["depth"])) == float(e["max_depth"]),
              f"t={t}: deepest contact {np.max(data['depth'])!r} != max_depth {e['max_depth']}")
        # The same double products as the writer's, so exactly equal.
        check(np.array_equal(data["force"], data["fn"][:, None] * normal),
              f"t={t}: force != fn * normal")
        a, b, wall = data["body_a"], data["body_b"], data["wall"]
        check(np.all((a >= 0) & (a < len(names))), f"t={t}: body_a out of range")
        check(np.all((b >= -1) & (b < len(names))), f"t={t}: body_b out of range")
        check(np.all((b == -1) == (wall >= 0)), f"t={t}: body_b = -1 exactly for walls")

    check(contact_frames > 0, "no frame has contacts: the scene does not test them")
    for f in failures:
        print("FAIL:", f)
    print(f"check_paraview: {len(order)} frames, {contact_frames} with contacts, "
          f"{len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
