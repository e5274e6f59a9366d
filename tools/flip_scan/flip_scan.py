"""Changes each byte of a table in turn (XOR 0x5a) and reads every damaged copy, as
tools/flip_scan/flip_scan.sh runs it (under MALLOC_PERTURB_):

  flip_scan.py python TABLE SCRATCH STRIDE   with the Python module, in this one process
  flip_scan.py info WRC TABLE SCRATCH STRIDE with `WRC info --json`, one process per copy

A copy must be refused (TableError; exit 2) or read exactly as the intact table is; a crash of
the Python module ends the scan, a crash of `wrc info` is counted. Prints the counts."""
import json
import subprocess
import sys

import numpy as np


def flipped(data, stride):
    for offset in range(0, len(data), stride):
        copy = bytearray(data)
        copy[offset] ^= 0x5A
        yield offset, bytes(copy)


def diagonal_points(table):
    axes = list(table.axes.values())
    longest = max(len(v) for v in axes)
    points = []
    for k in range(longest):
        node = [v[min(k, len(v) - 1)] for v in axes]
        middle = [0.5 * (v[k] + v[k + 1]) if k + 1 < len(v) else v[-1] for v in axes]
        points += [node, middle]
    return np.array(points)


def scan_python(path, scratch, stride):
    import wrc

    intact = wrc.Table(path)
    points = diagonal_points(intact)
    reference = intact.eval(points)
    data = open(path, "rb").read()
    counts = dict(offsets=0, refused=0, identical=0, warned=0, different=0)
    for offset, copy in flipped(data, stride):
        open(scratch, "wb").write(copy)
        counts["offsets"] += 1
        try:
            table = wrc.Table(scratch)
        except wrc.TableError:
            counts["refused"] += 1
            continue
        counts["warned"] += 1 if table.warning else 0
        same = all(np.array_equal(a, b, equal_nan=True)
                   for a, b in zip(_as_tuple(table.eval(points)), _as_tuple(reference)))
        counts["identical" if same else "different"] += 1
        if not same:
            print(f"flip_scan: offset {offset} opens with other numbers", file=sys.stderr)
    return counts


def _as_tuple(result):
    return result if isinstance(result, tuple) else (result,)


def scan_info(wrc_path, path, scratch, stride):
    run = lambda p: subprocess.run([wrc_path, "info", "--json", p], capture_output=True)
    reference = json.loads(run(path).stdout)
    reference.pop("file")
    data = open(path, "rb").read()
    counts = dict(offsets=0, refused=0, identical=0, crashed=0, different=0)
    for offset, copy in flipped(data, stride):
        open(scratch, "wb").write(copy)
        counts["offsets"] += 1
        r = run(scratch)
        if r.returncode < 0:
            counts["crashed"] += 1
            print(f"flip_scan: offset {offset}: wrc info died of signal {-r.returncode}",
                  file=sys.stderr)
        elif r.returncode == 2:
            counts["refused"] += 1
        else:
            shown = json.loads(r.stdout)
            shown.pop("file")
            counts["identical" if shown == reference and r.returncode == 0 else "different"] += 1
    return counts


if __name__ == "__main__":
    mode = sys.argv[1]
    if mode == "python":
        counts = scan_python(sys.argv[2], sys.argv[3], int(sys.argv[4]))
    else:
        counts = scan_info(sys.argv[2], sys.argv[3], sys.argv[4], int(sys.argv[5]))
    print(" ".join(f"{k} {v}" for k, v in counts.items()))
    sys.exit(0 if counts["different"] == 0 and counts.get("crashed", 0) == 0 else 1)
