"""deform_sandbox plays a scene as `sandbox run` does: the same state hash, bit for bit, and a saved state
resumed from Python continues the same run."""
import os
import re
import subprocess

import numpy as np

import deform_sandbox

SPEED = {"vehicle.start.speed_kmh": 40}


def cli_hash(tmp_path, *args):
    """The state hash `sandbox run` prints (the command is run now, not a remembered value)."""
    out = subprocess.run([os.environ["DEFORM_SANDBOX_CLI"], "run", "wall_crash", "--out", str(tmp_path / "cli"), *args],
                         check=True, capture_output=True, text=True).stdout
    found = re.search(r"state hash ([0-9a-f]{16})", out)
    assert found, out
    return found.group(1)


def test_state_hash_matches_the_command_line(tmp_path):
    run = deform_sandbox.Scene("wall_crash", set=SPEED)
    start_hash = run.state_hash()
    assert run.duration_s == 1.6 and run.time_s == 0
    while not run.finished:
        run.step()
    assert abs(run.time_s - run.duration_s) < 1e-9
    assert run.state_hash() != start_hash
    summary = run.summary()
    assert summary["state_hash"] == run.state_hash()
    assert summary["impacted"] and summary["residual_crush_m"] > 0
    assert run.state_hash() == cli_hash(tmp_path, "--set", "vehicle.start.speed_kmh=40")


def test_summary_is_summary_json(tmp_path):
    run = deform_sandbox.Scene("wall_crash")
    run.run_to_end()
    cli_hash(tmp_path)
    import json
    with open(tmp_path / "cli" / "summary.json") as f:
        written = json.load(f)
    ours = run.summary()
    assert set(ours) == set(written)
    for key in ("state_hash", "residual_crush_m", "impact_speed_mps", "steps", "cars"):
        assert ours[key] == written[key], key


def test_cars_expose_their_state_as_arrays():
    run = deform_sandbox.Scene("wall_crash", set=SPEED)
    car = run.cars[0]
    rest = car.rest_control_points()
    points = car.control_points()
    assert points.shape == rest.shape and points.shape[1] == 3 and not points.flags.writeable
    x0 = car.position_m.copy()
    run.advance(0.1)  # 50 steps at 500 Hz
    assert run.steps == 50
    v = car.velocity_mps
    assert v.shape == (3,) and abs(v[0] - 40 / 3.6) < 0.5  # still coasting at about 40 km/h
    assert abs((car.position_m[0] - x0[0]) - 0.1 * 40 / 3.6) < 0.05
    assert np.allclose(car.pose[:3, 3], car.position_m)
    assert abs(np.linalg.norm(car.orientation_wxyz) - 1) < 1e-12
    # Undamaged before the wall: the render mesh is the rest mesh, and the control points their rest places.
    vertices = car.mesh_vertices()
    assert vertices.dtype == np.float32 and vertices.shape[1] == 3 and len(vertices) > 1000
    assert np.abs(car.control_points() - rest).max() < 0.02
    run.run_to_end()
    dented = car.mesh_vertices()
    moved = np.linalg.norm(dented - vertices, axis=1)
    assert moved.max() > 0.1  # the front crushed by the wall
    assert np.median(moved) < moved.max() / 4  # locally, not the whole car


def test_save_and_resume_continue_the_same_run(tmp_path):
    run = deform_sandbox.Scene("wall_crash", set=SPEED)
    run.advance(0.3)
    path = str(tmp_path / "wall.state")
    run.save_state(path)
    saved_hash = run.state_hash()
    run.run_to_end()
    resumed = deform_sandbox.Scene.resume(path, set=SPEED)
    assert resumed.state_hash() == saved_hash and abs(resumed.time_s - 0.3) < 1e-9
    resumed.run_to_end()
    assert resumed.state_hash() == run.state_hash()
