#!/usr/bin/env python3
"""Writes the seed corpora of the fuzz targets, fuzz/corpus/<target>/: a few valid inputs (some
cut small from the real data in test/data and the configs in config/) and a few edge cases for
each. Run from anywhere; it rewrites the corpus folders. Only the standard library."""

import pathlib
import re
import shutil
import struct

FUZZ = pathlib.Path(__file__).resolve().parent
ROOT = FUZZ.parent
DATA = ROOT / "test" / "data"
CORPUS = FUZZ / "corpus"


def write_corpus(target, seeds):
    folder = CORPUS / target
    shutil.rmtree(folder, ignore_errors=True)
    folder.mkdir(parents=True)
    for name, content in seeds.items():
        (folder / name).write_bytes(content if isinstance(content, bytes) else content.encode())


# --- fuzz_cloud_msg: the message layout that fuzz/fuzz_cloud_msg.cpp reads ---------------------

FLOAT32, FLOAT64, UINT8, UINT16, UINT32 = 7, 8, 2, 4, 6


def message(width, height, point_step, row_step, fields, data, big_endian=False):
    out = struct.pack("<IIIIBB", width, height, point_step, row_step, int(big_endian),
                      len(fields))
    for name, offset, datatype, count in fields:
        out += struct.pack("<B", len(name)) + name.encode() + struct.pack("<IBI", offset,
                                                                            datatype, count)
    return out + data


XYZI = [("x", 0, FLOAT32, 1), ("y", 4, FLOAT32, 1), ("z", 8, FLOAT32, 1),
        ("intensity", 12, FLOAT32, 1)]


def cloud_seeds():
    points = [(1.0, 2.0, 3.0, 0.5), (-4.0, 5.5, -6.0, 1.0), (7.0, -8.0, 0.25, 0.0)]
    xyzi = b"".join(struct.pack("<4f", *p) for p in points)
    ring_time = XYZI + [("ring", 16, UINT16, 1), ("time", 18, FLOAT32, 1)]
    with_ring = b"".join(struct.pack("<4fHf", *p, i, 0.01 * i) for i, p in enumerate(points))
    ouster = [("x", 0, FLOAT64, 1), ("y", 8, FLOAT64, 1), ("z", 16, FLOAT64, 1),
              ("t", 24, UINT32, 1)]
    ouster_data = b"".join(struct.pack("<3dI", *p[:3], 25000000 * i)
                           for i, p in enumerate(points))
    padded = b"".join(struct.pack("<4f", *p) + b"\0" * 4 for p in points[:2]) * 2
    big = b"".join(struct.pack(">4f", *p) for p in points)
    # The first points of the real VLP-16 frame, with its ten fields (nebula's layout).
    vlp16 = DATA / "vlp16" / "vlp16_indoor.pcd"
    raw = vlp16.read_bytes()
    body = raw[raw.index(b"DATA binary\n") + len(b"DATA binary\n"):]
    nebula = XYZI[:3] + [("intensity", 12, UINT8, 1), ("return_type", 13, UINT8, 1),
                         ("channel", 14, UINT16, 1), ("azimuth", 16, FLOAT32, 1),
                         ("elevation", 20, FLOAT32, 1), ("distance", 24, FLOAT32, 1),
                         ("time_stamp", 28, UINT32, 1)]
    write_corpus("fuzz_cloud_msg", {
        "xyzi": message(3, 1, 16, 48, XYZI, xyzi),
        "ring_time": message(3, 1, 22, 66, ring_time, with_ring),
        "ouster_float64_ns": message(3, 1, 28, 84, ouster, ouster_data),
        "organized_row_padding": message(2, 2, 20, 40, XYZI, padded),
        "big_endian": message(3, 1, 16, 48, XYZI, big, big_endian=True),
        "vlp16_real_20_points": message(20, 1, 32, 640, nebula, body[:640]),
        "missing_z": message(3, 1, 16, 48, XYZI[:2], xyzi),
        "field_past_step": message(3, 1, 12, 36, XYZI, xyzi),
        "short_data": message(4, 1, 16, 64, XYZI, xyzi),
        "row_step_too_small": message(3, 1, 16, 20, XYZI, xyzi),
        "empty": message(0, 1, 16, 0, XYZI, b""),
    })


# --- fuzz_kitti_bin ------------------------------------------------------------------------------

def kitti_seeds():
    scan = (DATA / "kitti_seq07" / "velodyne" / "0000000000.bin").read_bytes()
    write_corpus("fuzz_kitti_bin", {
        "real_32_points": scan[:32 * 16],
        "empty": b"",
        "truncated_17_bytes": scan[:17],
        "nan_and_inf": struct.pack("<4f", float("nan"), float("inf"), -float("inf"), 0.0),
    })


# --- fuzz_pcd ------------------------------------------------------------------------------------

def lzf_compress(data):
    """liblzf's format with a plain greedy matcher (a back reference for every match of 3 bytes
    or more within 8 KiB), enough to give the fuzzer real back references."""
    out, literals, i = bytearray(), bytearray(), 0

    def flush():
        for start in range(0, len(literals), 32):
            chunk = literals[start:start + 32]
            out.append(len(chunk) - 1)
            out.extend(chunk)
        literals.clear()

    while i < len(data):
        best_length, best_distance = 0, 0
        for j in range(max(0, i - 8192), i):
            length = 0
            while (i + length < len(data) and data[j + length] == data[i + length]
                   and length < 264):
                length += 1
            if length > best_length:
                best_length, best_distance = length, i - j
        if best_length >= 3:
            flush()
            length, distance = best_length - 2, best_distance - 1
            if length < 7:
                out.append((length << 5) | (distance >> 8))
            else:
                out.extend([(7 << 5) | (distance >> 8), length - 7])
            out.append(distance & 0xFF)
            i += best_length
        else:
            literals.append(data[i])
            i += 1
    flush()
    return bytes(out)


def pcd_header(fields, sizes, types, counts, width, height, data):
    return (f"# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS {fields}\n"
            f"SIZE {sizes}\nTYPE {types}\nCOUNT {counts}\nWIDTH {width}\nHEIGHT {height}\n"
            f"VIEWPOINT 0 0 0 1 0 0 0\nPOINTS {width * height}\nDATA {data}\n").encode()


def pcd_seeds():
    ascii_lines = (DATA / "clustering_bench" / "points_noground").glob("*.pcd")
    text = next(ascii_lines).read_text().splitlines()
    points = text[text.index("DATA ascii") + 1:][:20]
    ascii_xyz = pcd_header("x y z", "4 4 4", "F F F", "1 1 1", len(points), 1, "ascii")
    ascii_xyz += ("\n".join(points) + "\n").encode()

    raw = (DATA / "vlp16" / "vlp16_indoor.pcd").read_bytes()
    body = raw[raw.index(b"DATA binary\n") + len(b"DATA binary\n"):][:20 * 32]
    nebula = ("x y z intensity return_type channel azimuth elevation distance time_stamp",
              "4 4 4 1 1 2 4 4 4 4", "F F F U U U F F F U", "1 1 1 1 1 1 1 1 1 1")
    binary = pcd_header(*nebula, 20, 1, "binary") + body
    # binary_compressed stores the records field by field.
    sizes = [4, 4, 4, 1, 1, 2, 4, 4, 4, 4]
    offsets = [sum(sizes[:k]) for k in range(len(sizes))]
    by_field = b"".join(body[i * 32 + offsets[k]:i * 32 + offsets[k] + sizes[k]]
                        for k in range(len(sizes)) for i in range(20))
    packed = lzf_compress(by_field)
    compressed = (pcd_header(*nebula, 20, 1, "binary_compressed") +
                  struct.pack("<II", len(packed), len(by_field)) + packed)

    ring_ascii = pcd_header("x y z intensity ring time", "4 4 4 4 2 4", "F F F F U F",
                            "1 1 1 1 1 1", 3, 1, "ascii")
    ring_ascii += b"1 2 3 0.5 0 0\n4 5 6 1 7 0.05\nnan nan nan 0 15 0.099\n"
    organized = pcd_header("x y z", "8 8 8", "F F F", "1 1 1", 2, 2, "binary")
    organized += b"".join(struct.pack("<3d", i, -i, 0.5 * i) for i in range(4))
    counted = pcd_header("x y z normal", "4 4 4 4", "F F F F", "1 1 1 3", 2, 1, "ascii")
    counted += b"1 2 3 0 0 1\n4 5 6 0 1 0\n"
    mismatch = ascii_xyz.replace(f"POINTS {len(points)}".encode(), b"POINTS 21")
    write_corpus("fuzz_pcd", {
        "ascii_real_20_points.pcd": ascii_xyz,
        "binary_real_20_points.pcd": binary,
        "binary_compressed_real_20_points.pcd": compressed,
        "ascii_ring_time_nan.pcd": ring_ascii,
        "binary_organized_float64.pcd": organized,
        "ascii_count_3.pcd": counted,
        "points_mismatch.pcd": mismatch,
        "no_data_line.pcd": b"VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\n",
    })


# --- fuzz_pose_files: every reader gets every seed -----------------------------------------------

def pose_seeds():
    seq07 = DATA / "kitti_seq07"
    poses = (seq07 / "poses.txt").read_text().splitlines()
    write_corpus("fuzz_pose_files", {
        "kitti_poses_real": "\n".join(poses[:3]) + "\n",
        "kitti_times_real": (seq07 / "times.txt").read_text(),
        "kitti_calib_real": (seq07 / "calib.txt").read_text(),
        "tum_poses": "# timestamp tx ty tz qx qy qz qw\n0.0 0 0 0 0 0 0 1\n"
                     "0.1 1.5 -0.25 0.01 0 0 0.0499792 0.9987503\n\n"
                     "0.2 3 -0.5 0.02 0 0 0.0998334 0.9950042\n",
        "kitti_pose_not_a_rotation": "0 1 0 0 1 0 0 0 0 0 1 0\n",
        "kitti_pose_nan": "1 0 0 nan 0 1 0 0 0 0 1 0\n",
        "tum_zero_quaternion": "0.0 1 2 3 0 0 0 0\n",
        "calib_two_tr_lines": "P0: 1 0 0\n" + "Tr: 1 0 0 0 0 1 0 0 0 0 1 0\n" * 2,
        "crlf_and_blank_lines": "0.0\r\n\r\n0.1\r\n",
    })


# --- fuzz_config ---------------------------------------------------------------------------------

def without_comments(yaml_text):
    lines = [re.sub(r"\s+#.*$", "", line) for line in yaml_text.splitlines()]
    return "\n".join(line for line in lines if line.strip() and not line.lstrip()
                     .startswith("#")) + "\n"


def config_seeds():
    minimal = "sensor:\n  rows: 16\n  columns: 1800\n"
    seeds = {name + ".yaml": without_comments((ROOT / "config" / (name + ".yaml")).read_text())
             for name in ("vlp16", "kitti_16rings")}
    seeds.update({
        "minimal.yaml": minimal,
        "flow_style.yaml": "{sensor: {rows: 4, beam_angles_deg: [-3, -1, 1, 3]}}\n",
        "anchor_alias.yaml": minimal + "mapping: &m {enabled: true}\nloop_closure: *m\n",
        "unknown_key.yaml": minimal + "  colums: 1800\n",
        "out_of_range.yaml": "sensor:\n  rows: 0\n",
        "sequence_as_key.yaml": "? [sensor]\n: {rows: 16}\n",
        "not_a_mapping.yaml": "- sensor\n- rows\n",
        "empty.yaml": "",
    })
    write_corpus("fuzz_config", seeds)


if __name__ == "__main__":
    cloud_seeds()
    kitti_seeds()
    pcd_seeds()
    pose_seeds()
    config_seeds()
    for folder in sorted(CORPUS.iterdir()):
        sizes = [path.stat().st_size for path in folder.iterdir()]
        print(f"{folder.name}: {len(sizes)} seeds, largest {max(sizes)} bytes")
