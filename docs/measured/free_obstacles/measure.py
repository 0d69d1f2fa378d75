#!/usr/bin/env python3
"""Runs the free-obstacle scenes with one or two sandbox binaries and prints the energy terms as tables: one
car (box_free, box_pinch, box_tight), then two cars pinching one box (two_pinch, west / east).

Usage: measure.py SANDBOX [SANDBOX_BEFORE] > free_obstacles.md
(docs/CRASH_CALIBRATION.md, "Free obstacles in the substeps")."""
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
CASES = [("box_free", m) for m in (10, 100)] + [("box_pinch", m) for m in (10, 100, 1000)] + \
        [("box_tight", m) for m in (10, 100)]
# Two cars pinching one box: each car's terms (west, then east).
TWO_CAR_CASES = [("two_pinch", m) for m in (10, 100, 1000)]


def run(sandbox, scene, mass_kg):
    with tempfile.TemporaryDirectory() as out:
        subprocess.run([sandbox, "run", os.path.join(HERE, scene + ".json"), "--set",
                        "obstacles[0].mass_kg=%g" % mass_kg, "--out", out],
                       check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        summary = json.load(open(os.path.join(out, "summary.json")))
    energies = [car["energy"] for car in summary["cars"]] if "cars" in summary else [summary["energy"]]
    return " / ".join("%.1f | %.1f | %.1f | %+.1f %%" % (e["plastic_work_J"] / 1e3, e["obstacle_work_J"] / 1e3,
                                                       e["contact_loss_J"] / 1e3,
                                                       100 * e["balance_error_J"] / e["kinetic_initial_J"])
                      for e in energies)


def main():
    binaries = sys.argv[1:]
    names = ["now"] if len(binaries) == 1 else ["now", "before"]
    head = "| scene | box kg | " + " | ".join(
        "%s: plastic kJ | box's work kJ | contact loss kJ | unexplained" % n for n in names) + " |"
    print(head)
    print("|" + "---|" * (2 + 4 * len(names)))
    for scene, mass in CASES:
        print("| %s | %g | %s |" % (scene, mass, " | ".join(run(b, scene, mass) for b in binaries)))
    print()
    print("Two cars (west / east):")
    print()
    print(head)
    print("|" + "---|" * (2 + 4 * len(names)))
    for scene, mass in TWO_CAR_CASES:
        cells = [run(b, scene, mass).split(" / ") for b in binaries]
        print("| %s | %g | %s |" % (scene, mass, " | ".join(
            " | ".join("%s / %s" % (w, e) for w, e in zip(c[0].split(" | "), c[1].split(" | ")))
            for c in cells)))


if __name__ == "__main__":
    main()
