"""Simulation.step's dict carries the step's solve report (visit_simulation_step_report): every field of
ARAP.report under the same name, with sane values, beside the step's own fields."""
import pytest

import iarap
from test_dynamics import bottom_of, single_thread  # noqa: F401 (the same scene, on one thread)

STEP_FIELDS = {"step", "time", "kinetic_energy", "elastic_energy", "potential_energy", "total_energy"}
STOP_REASONS = {"max_iterations", "energy_tolerance", "gradient_tolerance", "time_budget", "callback"}


def test_step_report_has_the_solve_fields(bunny):
    V, F = bunny
    bottom = bottom_of(V)
    solver = iarap.ARAP(V, F, bottom)
    solver.solve(V[bottom], iterations=1)
    sim = iarap.Simulation(V, F, bottom, dt=0.1, gravity=(0.0, -1.0, 0.0), density=0.2)
    for n in range(1, 4):
        report = sim.step()
        # ARAP.report adds the precomputation's times to the solve's fields; the step has the solve's.
        solve_fields = set(report) - STEP_FIELDS
        assert solve_fields <= set(solver.report)
        assert set(solver.report) - solve_fields == {k for k in solver.report if k.endswith("_ms")} - solve_fields
        assert {"iterations", "stop_reason", "energies", "gradient_norms", "penalty", "elapsed_ms"} <= solve_fields
        assert report["step"] == n
        assert 1 <= report["iterations"] <= 100  # default_step_options: 100
        assert report["converged"] and report["stop_reason"] in STOP_REASONS
        assert report["accelerator"] == "newton"
        assert len(report["energies"]) == report["iterations"] == len(report["accepted"])
        assert report["accepted"].dtype == bool
        assert report["solves"] >= report["iterations"]
        # The old names and the report's agree; they are the energies of the new positions.
        assert report["elastic_energy"] == report["arap_energy"]
        assert report["potential_energy"] == report["potential"]
        scale = abs(report["arap_energy"]) + abs(report["potential"]) + report["penalty"]
        assert report["arap_energy"] == pytest.approx(sim.elastic_energy, abs=1e-10 * scale)
        assert report["potential"] == pytest.approx(sim.potential_energy, abs=1e-10 * scale)
        assert report["potential"] < 0 < report["penalty"]  # falling, against its inertia
        assert report["energies"][-1] == pytest.approx(
            report["arap_energy"] + report["penalty"] + report["potential"], abs=1e-10 * scale)
        assert report["total_energy"] == pytest.approx(
            report["kinetic_energy"] + report["elastic_energy"] + report["potential_energy"], rel=1e-15)
