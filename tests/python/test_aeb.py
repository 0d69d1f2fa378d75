"""A driver in the loop: the automatic-emergency-braking example stops the car short of the wall that the
same car, coasting, hits."""
import aeb


def test_braking_loop_stops_short_of_the_wall():
    coasting = aeb.run_aeb(speed_kmh=40, threshold_m=9.0, aeb=False)
    assert coasting["impacted"] and coasting["impact_speed_mps"] > 10  # 40 km/h is 11.1 m/s
    braking = aeb.run_aeb(speed_kmh=40, threshold_m=9.0)
    assert braking["braked_at"] is not None and braking["braked_at"]["gap_m"] <= 9.0
    assert not braking["impacted"]
    assert braking["min_gap_m"] > 0
    assert braking["final_speed_mps"] < 0.1


def test_braking_late_lowers_the_impact_speed():
    late = aeb.run_aeb(speed_kmh=40, threshold_m=3.0)
    assert late["impacted"]
    assert 0 < late["impact_speed_mps"] < 40 / 3.6 - 1
