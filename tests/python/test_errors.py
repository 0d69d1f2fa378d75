"""Bad scene keys and values raise ValueError with the command line's message, naming the key."""
import os
import subprocess

import pytest

import deform_sandbox


def cli_error(key, value, out_dir):
    done = subprocess.run([os.environ["DEFORM_SANDBOX_CLI"], "run", "wall_crash", "--out", str(out_dir),
                           "--set", f"{key}={value}"], capture_output=True, text=True)
    assert done.returncode == 2
    return done.stderr.strip().removeprefix("sandbox: ")


@pytest.mark.parametrize("key,value", [
    ("vehicle.start.speed_kmhh", 40),         # unknown key
    ("vehicle.mass_kg", -5),                  # out of range
    ("vehicle.deformation.preset", "quick"),  # unknown name
])
def test_bad_keys_raise_value_error_naming_the_key(key, value, tmp_path):
    with pytest.raises(ValueError) as error:
        deform_sandbox.Scene("wall_crash", set={key: value})
    message = str(error.value)
    assert key.split(".")[-1] in message
    assert message == cli_error(key, value, tmp_path / "out")
    assert not (tmp_path / "out").exists()  # refused before any output


def test_unknown_scene_and_bad_inputs():
    with pytest.raises(ValueError, match="no_such_scene"):
        deform_sandbox.Scene("no_such_scene")
    run = deform_sandbox.Scene("wall_crash")
    with pytest.raises(ValueError, match="dt_s"):
        run.advance(-1.0)
    with pytest.raises(ValueError, match="throttle"):
        run.cars[0].drive(throttle=float("nan"))
