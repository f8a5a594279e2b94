# Ctrl-C during any long call of the module (Scene.probe, validate, test, simulate)
# reaches Python as KeyboardInterrupt at once, not when the call would have ended. Each
# case runs the call in a real Python interpreter (a subprocess), sends it SIGINT once
# the call has started, and measures how long the KeyboardInterrupt took to arrive.
import os
import signal
import subprocess
import sys
import time

import pytest

from conftest import ROOT

# A spring that keeps the loop's pace and the harness's scans' pace: a few us a call at
# t = 0 (a probe of a million points calls it two million times: seconds), about 0.2 ms
# a call later in a run (validate's and test's closed-loop scenarios: seconds of CPU,
# simulate's 3000 s run: ten minutes).
SCRIPT = """needs = {velocity = false, time = true}
function force(s)
  local a = 0
  for i = 1, 500 do a = a + i end
  if s.t > 0.05 then for i = 1, 20000 do a = a + i end end
  return -100 * s.x
end
"""

CALLS = {
    "probe": "scene.probe(numpy.linspace(-0.04, 0.04, 1000000))",
    "validate": "hapscene.validate(scene)",
    "test": "hapscene.test([SPEC])",
    "simulate": "hapscene.simulate(scene, duration=3000)",
}

CHILD = """
import sys, time
import numpy
import hapscene
SPEC = {spec!r}
scene = hapscene.load({env!r})
print("started", flush=True)
started = time.monotonic()
try:
    # Called again whenever it returns: a validate or test that ends early on its "pace"
    # check (a timing judgement, earlier on a busy machine) leaves the signal to the next.
    while True:
        {call}
except KeyboardInterrupt:
    print("interrupted", time.monotonic(), time.monotonic() - started, flush=True)
    sys.exit(0)
"""


@pytest.mark.parametrize("what", sorted(CALLS))
def test_ctrl_c_interrupts_a_long_call_promptly(what, tmp_path):
    env = tmp_path / "busy.lua"
    env.write_text(SCRIPT)
    spec = tmp_path / "busy.test.json"
    spec.write_text('{"environment": "busy.lua", "passes_validate": true}')
    child = subprocess.Popen(
        [sys.executable, "-c", CHILD.format(spec=str(spec), env=str(env), call=CALLS[what])],
        cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert child.stdout.readline().strip() == "started"
        time.sleep(0.5)  # well inside the (first) call
        sent = time.monotonic()
        child.send_signal(signal.SIGINT)
        out, err = child.communicate(timeout=5.0)  # the watchdog
    finally:
        if child.poll() is None:
            child.kill()
            child.wait()
    words = out.split()
    assert words and words[0] == "interrupted", (out, err)
    latency_s = float(words[1]) - sent
    print(f"{what}: KeyboardInterrupt {latency_s * 1e3:.1f} ms after SIGINT, {float(words[2]):.2f} s into the call")
    assert child.returncode == 0
    assert latency_s < 5.0
