"""The console's state view in a real browser: is the page still responsive with
8 vehicles x 2 managers running 100-state plans? Prints figures, asserts nothing.

The console serves a headless chromium (tests/console/browser.py) while the
traffic of bench/console_bench.py's state-view case goes over LCM (ttl=0): 16
plan structures of STATES states and statuses at RATE Hz with their plan_id,
live test values and 64 variables, the active leg moving every 2 s. Figures:
the time the page takes to build the 16 trees, the time of each update of the
view (all 16 columns) and the longest task the page ran (Long Tasks API: a task
over 50 ms is one a user would feel).
Run: tests/isolated_net.sh .venv/bin/python bench/chasm_view_page_bench.py
"""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import threading
import time
from pathlib import Path

import lcm

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "bench"), str(ROOT / "tests" / "console")]
from browser import Browser  # noqa: E402
from console_bench import STATES, URL, publish  # noqa: E402

SECONDS = float(os.environ.get("CONSOLE_BENCH_SECONDS", 15))
RATE = 5.0

INSTRUMENT = """(() => {
  window.__updates = []; window.__longest = 0; window.__build = 0;
  const update = cvUpdate, build = cvBuildTree;
  cvUpdate = now => { const t0 = performance.now(); update(now); __updates.push(performance.now() - t0); };
  cvBuildTree = (col, st) => { const t0 = performance.now(); build(col, st); __build += performance.now() - t0; };
  new PerformanceObserver(l => { for (const e of l.getEntries()) __longest = Math.max(__longest, e.duration); })
    .observe({ type: 'longtask', buffered: true });
})()"""


def main() -> None:
    argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter).parse_args()
    exe = shutil.which("chromium")
    if exe is None:
        print("chasm view page bench: skipped, no chromium (apt-get install chromium)")
        return
    proc = subprocess.Popen(
        [sys.executable, "-m", "tools.console", "--lcm-url", URL, "--port", "0"], stdout=subprocess.PIPE, text=True
    )
    port = int(proc.stdout.readline().split("http://", 1)[1].split("/")[0].rsplit(":", 1)[1])
    stop = threading.Event()
    lc = lcm.LCM(URL)
    threading.Thread(target=publish, args=(lc, RATE, stop, True), daemon=True).start()
    browser = Browser(exe)
    try:
        browser.open(f"http://127.0.0.1:{port}/")
        t0 = time.monotonic()
        browser.wait_for("typeof cvUpdate === 'function'", what="the page's script")
        browser.eval(INSTRUMENT)
        browser.wait_for(
            "[...document.querySelectorAll('.cv-col')].filter(c => c.querySelectorAll('li.active').length).length === 16",
            timeout=30,
            what="16 trees with their active path",
        )
        shown_s = time.monotonic() - t0
        first_longest = browser.eval("__longest")  # the page's load and the first structures
        browser.eval("__longest = 0; __updates = []")
        browser.eval("Object.values(CV.cols).forEach(c => { c.builtFor = null; })")  # build all 16 again, timed
        time.sleep(1.0)
        rebuild_longest = browser.eval("__longest")
        browser.eval("__longest = 0")
        time.sleep(SECONDS)
        u = browser.eval("__updates.slice(-1000)")
        build, longest = browser.eval("__build"), browser.eval("__longest")
        states = browser.eval("document.querySelectorAll('.cv-tree li').length")
    finally:
        browser.close()
        stop.set()
        proc.terminate()
        proc.wait(timeout=10)
    u.sort()
    print(f"state view page, 16 managers x {STATES}-state plans ({states} tree nodes), statuses at {RATE:.0f} Hz:")
    print(
        f"  trees drawn {shown_s:.1f} s after the page opened (structures come again every 10 s);"
        f" longest task while loading {first_longest:.0f} ms"
    )
    print(f"  building all 16 trees again: {build:.0f} ms of script, the longest task then {rebuild_longest:.0f} ms")
    print(
        f"  {len(u)} view updates in {SECONDS:.0f} s: median {u[len(u) // 2]:.2f} ms, max {u[-1]:.2f} ms;"
        f" longest task in those {SECONDS:.0f} s {longest:.0f} ms"
    )


if __name__ == "__main__":
    main()
