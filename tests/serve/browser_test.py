#!/usr/bin/python3
"""The live view in a real browser: headless Chromium (Debian's `chromium`) opens the page
of a simulated `hapscene run --ui`, sees the plotted values change, moves a parameter's
slider with the mouse, and the stream then shows the force of the new value.

Chromium is driven over the DevTools protocol on a pipe (--remote-debugging-pipe: JSON
messages ending in NUL on file descriptors 3 and 4), so nothing beyond the standard
library and the browser is needed. Without chromium the test fails: it is the point.

usage: browser_test.py --hapscene BUILD/hapscene [--screenshots DIR]
       browser_test.py --hapscene BUILD/hapscene --measure ENV --seconds T [--rounds R]
  --screenshots DIR   also writes DIR/live-view.png (1-D: a wall and a texture) and DIR/live-view-planar.png (2-D)
  --measure ENV       the loop's timing without and with the page open and streaming:
                      R rounds of `run ENV --duration T --quiet` and of the same run with
                      --ui and the page open in chromium, alternating; prints each
                      summary's deadline-miss, tick-compute and jitter lines
"""
import argparse
import base64
import fcntl
import json
import math
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time

SOURCE_DIR = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


class Browser:
    """Headless Chromium with one page, driven over the DevTools pipe."""

    def __init__(self, profile_dir, width=1400, height=900):
        executable = shutil.which("chromium") or shutil.which("chromium-browser")
        if executable is None:
            raise SystemExit("FAIL: chromium is not installed (apt-get install chromium; see .ci/install-deps)")
        to_browser_read, self.to_browser = os.pipe()
        self.from_browser, from_browser_write = os.pipe()
        # The browser reads commands on fd 3 and writes replies on fd 4. Python's pipes are
        # close-on-exec; the copies dup2 makes in the child are not, so only 3 and 4 pass.
        # (Moved above 10 first, so that neither dup2 overwrites the other's source.)
        high_read = fcntl.fcntl(to_browser_read, fcntl.F_DUPFD_CLOEXEC, 10)
        high_write = fcntl.fcntl(from_browser_write, fcntl.F_DUPFD_CLOEXEC, 10)
        os.close(to_browser_read)
        os.close(from_browser_write)
        def child_fds():
            os.dup2(high_read, 3)
            os.dup2(high_write, 4)
        self.process = subprocess.Popen(
            [executable, "--headless=new", "--remote-debugging-pipe", "--no-sandbox", "--disable-gpu",
             "--no-first-run", "--no-default-browser-check", "--disable-extensions", "--hide-scrollbars",
             "--user-data-dir=" + profile_dir, "--window-size=%d,%d" % (width, height), "about:blank"],
            close_fds=False, preexec_fn=child_fds, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        to_browser_read, from_browser_write = high_read, high_write
        os.close(to_browser_read)
        os.close(from_browser_write)
        self.next_id = 0
        self.buffer = b""
        self.session = None
        self.width, self.height = width, height

    def send(self, method, params=None, session=True):
        self.next_id += 1
        message = {"id": self.next_id, "method": method, "params": params or {}}
        if session and self.session:
            message["sessionId"] = self.session
        os.write(self.to_browser, json.dumps(message).encode() + b"\0")
        while True:
            reply = self.read()
            if reply.get("id") == self.next_id:
                if "error" in reply:
                    raise RuntimeError("%s: %s" % (method, reply["error"]))
                return reply.get("result", {})

    def read(self):
        while b"\0" not in self.buffer:
            chunk = os.read(self.from_browser, 1 << 16)
            if not chunk:
                raise RuntimeError("chromium closed the DevTools pipe")
            self.buffer += chunk
        message, self.buffer = self.buffer.split(b"\0", 1)
        return json.loads(message)

    def open(self, url):
        target = self.send("Target.createTarget", {"url": "about:blank"}, session=False)
        attached = self.send("Target.attachToTarget", {"targetId": target["targetId"], "flatten": True}, session=False)
        self.session = attached["sessionId"]
        self.send("Page.enable")
        self.send("Emulation.setDeviceMetricsOverride",
                  {"width": self.width, "height": self.height, "deviceScaleFactor": 1, "mobile": False})
        self.send("Page.navigate", {"url": url})

    def evaluate(self, expression):
        result = self.send("Runtime.evaluate", {"expression": expression, "returnByValue": True})
        if "exceptionDetails" in result:
            raise RuntimeError("page: %s" % result["exceptionDetails"])
        return result["result"].get("value")

    def click(self, x, y):
        for kind in ("mouseMoved", "mousePressed", "mouseReleased"):
            self.send("Input.dispatchMouseEvent",
                      {"type": kind, "x": x, "y": y, "button": "left", "clickCount": 1 if kind != "mouseMoved" else 0})

    def mouse(self, kind, x, y):
        """One mouse event: "mousePressed", "mouseMoved" (with the left button held) or "mouseReleased"."""
        self.send("Input.dispatchMouseEvent", {"type": kind, "x": x, "y": y, "button": "left",
                                               "buttons": 1 if kind != "mouseReleased" else 0,
                                               "clickCount": 1 if kind != "mouseMoved" else 0})

    def screenshot(self, path):
        data = self.send("Page.captureScreenshot", {"format": "png"})["data"]
        with open(path, "wb") as out:
            out.write(base64.b64decode(data))

    def close(self):
        try:
            self.send("Browser.close", session=False)
        except Exception:
            pass
        try:
            self.process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.process.kill()


def wait_for(what, condition, timeout_s=20.0):
    until = time.monotonic() + timeout_s
    while time.monotonic() < until:
        value = condition()
        if value:
            return value
        time.sleep(0.1)
    raise AssertionError("timed out waiting for " + what)


def page_state(browser):
    """What the page shows, for a failure's message."""
    try:
        return browser.evaluate("JSON.stringify({view: window.hapsceneView && Object.assign({}, window.hapsceneView, {scene: undefined}),"
                                " connection: document.getElementById('connection').textContent})")
    except Exception as error:  # the page itself may be the problem
        return "(page not readable: %s)" % error


def start_run(hapscene, environment, extra):
    """`hapscene run ENV --ui` with the simulated Hapkit; returns the process and the URL."""
    process = subprocess.Popen([hapscene, "run", environment, "--ui", "--quiet", "--duration", "120s"] + extra,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    until = time.monotonic() + 20
    while time.monotonic() < until:
        line = process.stderr.readline()
        if not line:
            break
        if line.startswith("live view: "):
            return process, line[len("live view: "):].strip()
    process.kill()
    raise AssertionError("hapscene run --ui printed no URL: " + process.stderr.read())


def end_run(process):
    process.send_signal(signal.SIGINT)
    out, err = process.communicate(timeout=20)
    return out, err


class RunOutputOnFailure:
    """`with RunOutputOnFailure(process):` ends the run on leaving, and when a check failed
    prints what the run said (its summary tells why it ended)."""

    def __init__(self, process):
        self.process = process
        self.out = self.err = ""

    def __enter__(self):
        return self

    def __exit__(self, kind, value, traceback):
        self.out, self.err = end_run(self.process)
        if kind is not None:
            print("the run printed:\n" + self.out + self.err, file=sys.stderr)
        return False


def check_plots_read(browser, what):
    """Every plot's ticks are round numbers (steps of 1, 2 or 5 times a power of ten, the
    values multiples of the step), and every line or mark a plot drew has its key in the
    plot's title."""
    info = browser.evaluate("""(() => {
        const v = window.hapsceneView;
        const titles = {'plot-position': 'position-title', 'plot-force': 'force-title', 'plot-trace': 'trace-title'};
        const out = {};
        for (const [plot, title] of Object.entries(titles)) {
          out[plot] = {ticks: v.ticks[plot], drawn: v.drawn[plot],
                       keys: Array.from(document.querySelectorAll('#' + title + ' .key')).map((k) => k.dataset.key)};
        }
        return out;
    })()""")
    for plot, d in info.items():
        for axis in ("x", "y"):
            values = d["ticks"][axis]
            assert len(values) >= 3, (what, plot, axis, values)
            step = values[1] - values[0]
            mantissa = step / 10 ** math.floor(math.log10(step) + 1e-9)
            assert any(abs(mantissa - m) < 1e-6 for m in (1, 2, 5)), (what, plot, axis, values)
            for a, b in zip(values, values[1:]):
                assert abs((b - a) - step) < 1e-9 * max(1.0, abs(step)), (what, plot, axis, values)
            for v in values:
                assert abs(v / step - round(v / step)) < 1e-6, (what, plot, axis, values)
        missing = [name for name in d["drawn"] if name not in d["keys"]]
        assert d["drawn"] and not missing, (what, plot, d["drawn"], d["keys"])
    print("%s: round ticks and a key for every line: %s" % (what, ", ".join(
        "%s %s" % (plot, "/".join(d["drawn"])) for plot, d in info.items())))


def check_one_dof(browser, hapscene, scratch, screenshots):
    environment = os.path.join(scratch, "spring.json")
    shutil.copy(os.path.join(SOURCE_DIR, "environments", "spring.json"), environment)
    # The hand sweeps the handle across the workspace; the spring's force at each tick is
    # -K x, so the stream shows the stiffness in force.
    process, url = start_run(hapscene, environment, [])
    try:
        browser.open(url)
        wait_for("the page to draw ticks", lambda: browser.evaluate(
            "window.hapsceneView && window.hapsceneView.frames > 5 && window.hapsceneView.samples > 100"), timeout_s=60)
        first = browser.evaluate("window.hapsceneView.plotted")
        time.sleep(1.0)
        second = browser.evaluate("window.hapsceneView.plotted")
        assert second["t_s"] > first["t_s"], (first, second)
        assert second["x_m"] != first["x_m"] or second["output_N"] != first["output_N"], (first, second)
        print("plotted values change: t %.3f -> %.3f s, x %.4f -> %.4f m" %
              (first["t_s"], second["t_s"], first["x_m"], second["x_m"]))
        check_plots_read(browser, "1-DOF")

        # Move the stiffness slider with the mouse to about 3/4 of its range.
        box = browser.evaluate("""(() => {
            const r = document.querySelector('input[type=range][data-param="0:stiffness"]').getBoundingClientRect();
            return {left: r.left, top: r.top, width: r.width, height: r.height};
        })()""")
        before = browser.evaluate("window.hapsceneView.scene.parameters[0].value")
        browser.click(box["left"] + 0.75 * box["width"], box["top"] + box["height"] / 2)
        stiffness = wait_for("the change to be taken", lambda: (
            browser.evaluate("window.hapsceneView.changes > 0 && window.hapsceneView.scene.parameters[0].value")), timeout_s=30)
        assert abs(stiffness - before) > 10, (before, stiffness)
        print("slider moved: stiffness %.1f -> %.1f N/m (%s)" % (before, stiffness,
              browser.evaluate("document.getElementById('unsaved').textContent")))

        # The stream shows the new force: -K x with the new K, once the cross-fade is over.
        def new_force():
            last = browser.evaluate("window.hapsceneView.last")
            expected = -stiffness * last["x_m"]
            return last if abs(last["x_m"]) > 0.002 and abs(last["force_N"] - expected) < 1e-9 * max(1.0, abs(expected)) else None
        last = wait_for("the stream to show -K x with K = %.1f N/m" % stiffness, new_force, timeout_s=30)
        print("the stream shows the new force: %.4f N at x %.4f m (-K x = %.4f N; before, %.4f N)" %
              (last["force_N"], last["x_m"], -stiffness * last["x_m"], -before * last["x_m"]))
    finally:
        out, err = end_run(process)
    assert "live view " in out, out
    print(out.strip().splitlines()[-1] if out.strip() else "")
    with open(environment) as env:
        assert env.read() == open(os.path.join(SOURCE_DIR, "environments", "spring.json")).read(), "the file changed without save"


def check_one_dof_sketch(browser, hapscene, scratch, screenshots):
    """A 1-D scene is drawn, not only its trace: the wall's solid side and the texture's
    fields under the force curve at rest, the handle now, each with its key; the ticks round."""
    environment = os.path.join(scratch, "wall-texture.json")
    with open(environment, "w") as out:
        json.dump({"name": "wall and texture", "effects": [
            {"type": "wall", "position": "10 mm", "stiffness": "300 N/m", "solid": "above"},
            {"type": "texture", "width": "5 mm", "spacing": "5 mm", "damping": "2 N*s/m", "offset": "0 mm"}]}, out)
    process, url = start_run(hapscene, environment, [])
    with RunOutputOnFailure(process):
        browser.open(url)
        wait_for("the page to draw the scene", lambda: browser.evaluate(
            "window.hapsceneView && window.hapsceneView.frames > 5"), timeout_s=60)
        drawn = browser.evaluate("window.hapsceneView.drawn['plot-trace']")
        for mark in ("solid", "field", "static", "handle", "commanded", "asked", "limit"):
            assert mark in drawn, (mark, drawn)
        curve = browser.evaluate("window.hapsceneView.scene.force_curve")
        at_20mm = curve["output_N"][curve["x_m"].index(min(curve["x_m"], key=lambda x: abs(x - 0.02)))]
        assert abs(at_20mm - (-3.0)) < 1e-9, at_20mm  # -K (x - xw) above the wall
        check_plots_read(browser, "1-DOF scene")

        # Feel it without hardware: press on the plot at -30 mm, drag to -20 mm; the hand
        # takes the handle there; let go, and the hand's sweep has it again.
        box = browser.evaluate("""(() => {
            const r = document.getElementById('plot-trace').getBoundingClientRect();
            return {left: r.left, top: r.top, width: r.width, height: r.height};
        })()""")
        lo, hi = -50.0, 45.0  # the Hapkit's workspace, mm
        at = lambda mm: box["left"] + 52 + (mm - lo) / (hi - lo) * (box["width"] - 62)
        middle = box["top"] + box["height"] / 2
        browser.mouse("mousePressed", at(-30.0), middle)
        wait_for("the hand to take the handle to -30 mm", lambda: browser.evaluate(
            "window.hapsceneView.last.x_m < -0.027 && window.hapsceneView.last.x_m"), timeout_s=30)
        for mm in (-28.0, -25.0, -22.0, -20.0):
            browser.mouse("mouseMoved", at(mm), middle)
            time.sleep(0.05)
        followed = wait_for("the handle to follow the pointer to -20 mm", lambda: browser.evaluate(
            "Math.abs(window.hapsceneView.last.x_m + 0.020) < 0.002 && window.hapsceneView.last.x_m"), timeout_s=30)
        browser.mouse("mouseReleased", at(-20.0), middle)
        wait_for("the hand to be let go", lambda: browser.evaluate(
            "window.hapsceneView.hand && window.hapsceneView.hand.hand === 'released'"), timeout_s=30)
        print("the pointer took the hand: the handle followed to %.1f mm, then was let go" % (followed * 1e3))
        if screenshots:
            browser.screenshot(os.path.join(screenshots, "live-view.png"))
        print("the 1-D scene is drawn: " + "/".join(drawn))


def check_planar(browser, hapscene, scratch, screenshots):
    environment = os.path.join(scratch, "box.json")
    shutil.copy(os.path.join(SOURCE_DIR, "environments", "planar", "haplink_box_inside.json"), environment)
    process, url = start_run(hapscene, environment, ["--hand", "circle"])
    try:
        browser.open(url)
        wait_for("the plane to draw", lambda: browser.evaluate(
            "window.hapsceneView && window.hapsceneView.frames > 5 && window.hapsceneView.samples > 1500"), timeout_s=60)
        last = browser.evaluate("window.hapsceneView.last")
        assert "y_m" in last and "output_y_N" in last, last
        check_plots_read(browser, "2-DOF")
        if screenshots:
            browser.screenshot(os.path.join(screenshots, "live-view-planar.png"))
    finally:
        end_run(process)


BOOM_SCRIPT = """-- says hello on its first call, faults after 50 ms
local said = false
function force(s)
  if not said then log('hello from the first call') said = true end
  if s.t > 0.05 then error('boom') end
  return 0
end
"""


def check_script_fault(browser, hapscene, scratch):
    """A script that faults inside the loop: the page shows its located message, once; and the
    line it logged on its first call, a second before the page opened, is in the page's log."""
    with open(os.path.join(scratch, "boom.lua"), "w") as out:
        out.write(BOOM_SCRIPT)
    environment = os.path.join(scratch, "boom.json")
    with open(environment, "w") as out:
        json.dump({"name": "boom", "effects": [{"type": "spring", "stiffness": "100 N/m"},
                                               {"type": "script", "file": "boom.lua"}]}, out)
    process, url = start_run(hapscene, environment, [])
    with RunOutputOnFailure(process):
        time.sleep(1.0)  # the hello and the fault happen before the page opens
        browser.open(url)
        log = wait_for("the log from before the page opened", lambda: browser.evaluate(
            "Array.from(document.querySelectorAll('#log li')).map((e) => e.textContent).join('\\n')"), timeout_s=60)
        assert "hello from the first call" in log, log
        shown = wait_for("the page to show the script's fault", lambda: browser.evaluate(
            "Array.from(document.querySelectorAll('#faults .fault')).map((e) => e.textContent).join('\\n')"), timeout_s=60)
        assert "boom.lua:5: boom" in shown, shown
        # More events come; the fault stays shown once.
        events = browser.evaluate("window.hapsceneView.events")
        wait_for("more events", lambda: browser.evaluate("window.hapsceneView.events") > events + 20, timeout_s=30)
        count = browser.evaluate("document.querySelectorAll('#faults .fault').length")
        assert count == 1, count
        scripts = browser.evaluate("document.getElementById('st-scripts').textContent")
        assert scripts == "disabled now: 1, faults in the run: 1", scripts
        print("the page shows the script fault once: " + shown)
        print("and the log from before it opened: " + log.splitlines()[0])


def stall(process, seconds):
    """Stops the run's process for `seconds` (a stall of the system, as a busy machine makes)."""
    process.send_signal(signal.SIGSTOP)
    time.sleep(seconds)
    process.send_signal(signal.SIGCONT)


def check_overruns(browser, hapscene, scratch):
    """Deadline misses past the limits: a simulated run reports them in the log and runs on;
    asked to stop on them (--overruns stop), it ends and the page shows why, as the terminal does."""
    environment = os.path.join(scratch, "spring-overruns.json")
    shutil.copy(os.path.join(SOURCE_DIR, "environments", "spring.json"), environment)
    for response in ("report", "stop"):
        process, url = start_run(hapscene, environment, [] if response == "report" else ["--overruns", "stop"])
        with RunOutputOnFailure(process) as run:
            browser.open(url)
            wait_for("the stream", lambda: browser.evaluate("window.hapsceneView && window.hapsceneView.events > 5"),
                     timeout_s=60)
            stall(process, 0.3)  # 300 deadlines missed: more than 100 within 1000
            log = lambda: browser.evaluate("Array.from(document.querySelectorAll('#log li')).map((e) => e.textContent).join('\\n')")
            if response == "report":
                shown = wait_for("the log to tell of the limit passed",
                                 lambda: "frequent overruns" in log() and log(), timeout_s=30)
                assert "reported only, the run went on" in shown, shown
                events = browser.evaluate("window.hapsceneView.events")
                wait_for("the run to go on", lambda: browser.evaluate("window.hapsceneView.events") > events + 20, timeout_s=30)
                assert not browser.evaluate("window.hapsceneView.ended")
                print("a simulated run passed the overrun limits and went on: " + shown.splitlines()[-1])
            else:
                wait_for("the run to end", lambda: browser.evaluate("window.hapsceneView.ended"), timeout_s=30)
                end = browser.evaluate("window.hapsceneView.end")
                assert end["reason"] == "overrun_fault" and end["fault"], end
                shown = browser.evaluate("document.querySelector('#faults .run-fault').textContent")
                assert shown.startswith("FAULT: frequent overruns at ") and "zero force commanded, run stopped" in shown, shown
                connection = browser.evaluate("document.getElementById('connection').textContent")
                assert connection == "run stopped: fault", connection
                print("the page shows the fault that ended the run: " + shown)
        # The terminal says the same.
        said = "FAULT            frequent overruns" if response == "stop" else "past the limit   frequent overruns"
        assert said in run.out, run.out


def timing_lines(summary):
    keep = ("deadline misses", "tick compute", "wake-up jitter", "live view")
    return [line.strip() for line in summary.splitlines() if line.strip().startswith(keep)]


def measure(hapscene, environment, seconds, rounds):
    scratch = tempfile.mkdtemp(prefix="hapscene_measure_")
    try:
        for round_index in range(rounds):
            plain = subprocess.run([hapscene, "run", environment, "--duration", "%gs" % seconds, "--quiet"],
                                   capture_output=True, text=True)
            print("round %d without the page:" % (round_index + 1))
            for line in timing_lines(plain.stdout):
                print("  " + line)
            browser = Browser(os.path.join(scratch, "profile%d" % round_index))
            try:
                process = subprocess.Popen([hapscene, "run", environment, "--ui", "--quiet", "--duration", "%gs" % seconds],
                                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
                url = None
                while url is None:
                    line = process.stderr.readline()
                    if not line:
                        raise AssertionError("no URL")
                    if line.startswith("live view: "):
                        url = line[len("live view: "):].strip()
                browser.open(url)
                out, _ = process.communicate(timeout=seconds + 60)
                frames = browser.evaluate("window.hapsceneView ? window.hapsceneView.frames : 0")
            finally:
                browser.close()
            print("round %d with the page open and streaming (%s frames drawn):" % (round_index + 1, frames))
            for line in timing_lines(out):
                print("  " + line)
    finally:
        shutil.rmtree(scratch, ignore_errors=True)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--hapscene", required=True)
    parser.add_argument("--screenshots")
    parser.add_argument("--measure")
    parser.add_argument("--seconds", type=float, default=30.0)
    parser.add_argument("--rounds", type=int, default=2)
    args = parser.parse_args()
    if args.measure:
        measure(args.hapscene, args.measure, args.seconds, args.rounds)
        return
    scratch = tempfile.mkdtemp(prefix="hapscene_browser_")
    browser = Browser(os.path.join(scratch, "profile"))
    try:
        try:
            check_one_dof(browser, args.hapscene, scratch, args.screenshots)
            check_one_dof_sketch(browser, args.hapscene, scratch, args.screenshots)
            check_planar(browser, args.hapscene, scratch, args.screenshots)
            check_script_fault(browser, args.hapscene, scratch)
            check_overruns(browser, args.hapscene, scratch)
        except AssertionError:
            print("the page: " + page_state(browser), file=sys.stderr)
            raise
    finally:
        browser.close()
        shutil.rmtree(scratch, ignore_errors=True)
    print("PASS live view in headless chromium")


if __name__ == "__main__":
    main()
