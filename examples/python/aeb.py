#!/usr/bin/python3
"""Automatic emergency braking in the loop: the wall crash with the car started further back, driven from
Python. Each step the gap from the car's front (its foremost control point, in the world) to the wall's
face is measured; below the threshold the controller takes the wheel and brakes fully. Reports the gap
and speed at which it braked, and the impact speed it achieved (0 when it stopped short of the wall).

    PYTHONPATH=build/python /usr/bin/python3 examples/python/aeb.py --speed-kmh 40 --threshold-m 9
"""
import argparse

import numpy as np

import deform_sandbox


def front_gap_m(run, car, wall):
    """Distance along the world X axis from the car's foremost point to the wall's near face [m]."""
    pose = car.pose
    points = car.control_points() @ pose[:3, :3].T + pose[:3, 3]
    face_x = wall["position_m"][0] - wall["size_m"][0] / 2
    return face_x - points[:, 0].max()


def run_aeb(speed_kmh=40.0, threshold_m=9.0, start_x_m=-15.0, duration_s=3.0, aeb=True):
    """Plays wall_crash from start_x_m at speed_kmh, braking fully once the gap falls below threshold_m
    (never, with aeb=False). Returns what happened as a dict."""
    run = deform_sandbox.Scene("wall_crash", set={
        "vehicle.start.speed_kmh": speed_kmh,
        "vehicle.start.position_m": [start_x_m, 0],
        "vehicle.drive.keys": [],  # no scripted braking: the car coasts unless the controller brakes
        "duration_s": duration_s,
    })
    car, wall = run.cars[0], run.obstacles[0]
    braked_at = None
    min_gap_m = np.inf
    while not run.finished:
        gap_m = front_gap_m(run, car, wall)
        min_gap_m = min(min_gap_m, gap_m)
        if aeb and braked_at is None and gap_m < threshold_m:
            braked_at = {"time_s": run.time_s, "gap_m": gap_m, "speed_mps": car.forward_speed_mps}
            car.drive(brake=1.0)
        run.step()
    summary = run.summary()
    return {
        "impacted": summary["impacted"],
        "impact_speed_mps": summary["impact_speed_mps"] if summary["impacted"] else 0.0,
        "min_gap_m": float(min_gap_m),
        "final_speed_mps": summary["final_speed_mps"],
        "braked_at": braked_at,
        "residual_crush_m": summary["residual_crush_m"],
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--speed-kmh", type=float, default=40.0)
    parser.add_argument("--threshold-m", type=float, default=9.0, help="brake below this gap to the wall")
    parser.add_argument("--start-x-m", type=float, default=-15.0, help="start position (the wall face is at 5.1 m)")
    args = parser.parse_args()
    result = run_aeb(args.speed_kmh, args.threshold_m, args.start_x_m)
    braked = result["braked_at"]
    if braked:
        print(f"braked at t = {braked['time_s']:.3f} s, {braked['gap_m']:.2f} m from the wall, "
              f"at {braked['speed_mps'] * 3.6:.1f} km/h")
    else:
        print("never braked (the gap stayed above the threshold)")
    if result["impacted"]:
        print(f"impact at {result['impact_speed_mps'] * 3.6:.1f} km/h "
              f"(from {args.speed_kmh:.1f} km/h), residual crush {result['residual_crush_m']:.3f} m")
    else:
        print(f"stopped short of the wall: closest gap {result['min_gap_m']:.2f} m, impact speed 0 km/h")


if __name__ == "__main__":
    main()
