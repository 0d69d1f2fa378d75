#!/usr/bin/python3
"""Residual crush against impact speed: the wall crash played at several speeds through the Python module,
plotted with matplotlib (Debian's python3-matplotlib) into crush_vs_speed.png.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/crush_sweep.py --speeds 16 32 48 56 64
"""
import argparse

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt

import deform_sandbox


def sweep(speeds_kmh):
    """(measured impact speed, residual crush, max dynamic crush) per start speed [km/h, m, m]."""
    rows = []
    for speed in speeds_kmh:
        run = deform_sandbox.Scene("wall_crash", set={"vehicle.start.speed_kmh": speed})
        run.run_to_end()
        s = run.summary()
        rows.append((s["impact_speed_mps"] * 3.6, s["residual_crush_m"], s["max_dynamic_crush_m"]))
        print(f"{speed:5.1f} km/h (impact {rows[-1][0]:5.1f} km/h): residual crush {s['residual_crush_m']:.3f} m, "
              f"max dynamic crush {s['max_dynamic_crush_m']:.3f} m, state hash {s['state_hash']}")
    return rows


def plot(rows, path):
    speeds = [r[0] for r in rows]
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(speeds, [r[1] for r in rows], "o-", label="residual crush")
    ax.plot(speeds, [r[2] for r in rows], "s--", label="max dynamic crush")
    ax.set_xlabel("impact speed [km/h]")
    ax.set_ylabel("crush [m]")
    ax.set_title("wall_crash: crush against speed")
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--speeds", type=float, nargs="+", default=[16, 32, 48, 56, 64])
    parser.add_argument("--out", default="crush_vs_speed.png")
    args = parser.parse_args()
    plot(sweep(args.speeds), args.out)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
