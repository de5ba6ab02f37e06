"""`import iarap` makes the library's OpenMP threads wait passively, as the iarap tool does, unless the user
chose a policy (issue 43). Read from libgomp itself: its report of its settings (OMP_DISPLAY_ENV=VERBOSE,
printed when the runtime loads) in a fresh interpreter, where a spinning wait shows GOMP_SPINCOUNT 300000
(the default) or 30000000000 (active) and a passive one 0."""
import os
import re
import subprocess
import sys

import pytest

import iarap


def omp_settings(**environment):
    """(OMP_WAIT_POLICY in os.environ after the import, libgomp's OMP_WAIT_POLICY, its GOMP_SPINCOUNT)."""
    env = {k: v for k, v in os.environ.items() if k not in ("OMP_WAIT_POLICY", "GOMP_SPINCOUNT")}
    env.update(environment, OMP_DISPLAY_ENV="VERBOSE",
               PYTHONPATH=os.path.dirname(os.path.dirname(iarap.__file__)))
    run = subprocess.run([sys.executable, "-c", "import os, iarap; print(os.environ['OMP_WAIT_POLICY'])"],
                         env=env, capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    policy = re.search(r"OMP_WAIT_POLICY = '(\w+)'", run.stderr)
    spin = re.search(r"GOMP_SPINCOUNT = '(\d+)'", run.stderr)
    assert policy and spin, f"libgomp printed no settings:\n{run.stderr}"
    return run.stdout.strip(), policy.group(1), int(spin.group(1))


def test_import_makes_waits_passive():
    assert omp_settings() == ("passive", "PASSIVE", 0)


@pytest.mark.parametrize("choice, shown", [("active", "ACTIVE"), ("passive", "PASSIVE")])
def test_a_policy_the_user_set_is_kept(choice, shown):
    environment, policy, spin = omp_settings(OMP_WAIT_POLICY=choice)
    assert (environment, policy) == (choice, shown)
    assert (spin > 0) == (choice == "active")
