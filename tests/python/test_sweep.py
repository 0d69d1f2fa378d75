"""The crush sweep example: residual crush grows with impact speed, and the plot is written."""
import crush_sweep


def test_crush_grows_with_speed_and_is_plotted(tmp_path):
    rows = crush_sweep.sweep([20, 50])
    (slow_kmh, slow_crush, _), (fast_kmh, fast_crush, fast_dynamic) = rows
    assert 18 < slow_kmh < 21 and 47 < fast_kmh < 51  # measured at impact, after 2.4 m of coasting
    assert 0 < slow_crush < fast_crush <= fast_dynamic
    path = tmp_path / "crush.png"
    crush_sweep.plot(rows, str(path))
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
