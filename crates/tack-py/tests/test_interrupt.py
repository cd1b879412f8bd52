"""Ctrl-C stops a long run with KeyboardInterrupt within a few seconds."""

import os
import signal
import subprocess
import sys
import time

import pytest

CHILD = r"""
import sys
import tack

scene = sys.argv[1]
print("ready", flush=True)
try:
    # About a minute of work: a finely resolved sphere retracted in tiny steps.
    tack.run(scene, overrides={"grid.n": 192, "grid.dx": 0.075,
                               "protocol.unload_step": 0.0005})
except KeyboardInterrupt:
    print("interrupted", flush=True)
    sys.exit(42)
print("finished", flush=True)
"""


@pytest.mark.skipif(os.name != "posix", reason="SIGINT")
def test_sigint_stops_a_long_run(repo):
    child = subprocess.Popen(
        [sys.executable, "-c", CHILD, str(repo / "data/examples/smooth_jkr_sphere.toml")],
        stdout=subprocess.PIPE,
        text=True,
    )
    try:
        assert child.stdout.readline().strip() == "ready"
        time.sleep(1.5)  # well inside the solve
        assert child.poll() is None, "the run ended before the signal"
        sent = time.perf_counter()
        child.send_signal(signal.SIGINT)
        code = child.wait(timeout=30)
        elapsed = time.perf_counter() - sent
    finally:
        if child.poll() is None:
            child.kill()
    assert code == 42, child.stdout.read()
    assert child.stdout.read().strip() == "interrupted"
    print(f"stopped {elapsed:.3f} s after SIGINT")
    assert elapsed < 3.0, f"took {elapsed:.2f} s to stop"
