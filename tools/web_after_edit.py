#!/usr/bin/env python3
"""Times the first click after an edit in `isegman serve` (a measurement, not a test).

Starts the server on a scene with a fresh embedding cache, waits for the segmentation,
clicks in camera 0, makes an edit (remove the clicked object, or recolour a strip at
the left edge of camera 0), waits PAUSE seconds (a user looking at the result), clicks
again and prints JSON: the seconds from the click request to the end of its job, and the
server's log lines about the views (kept / re-rendered).

  tools/web_after_edit.py build/isegman ../shared/fixtures/fern/scene remove-object 0
  tools/web_after_edit.py build/isegman ../shared/fixtures/fern/scene edge-strip 100
"""
import json
import shutil
import subprocess
import sys
import tempfile
import time
import urllib.request


def main():
    if len(sys.argv) != 5 or sys.argv[3] not in ("remove-object", "edge-strip"):
        sys.exit(__doc__)
    binary, scene, scenario, pause = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4])
    work = tempfile.mkdtemp(prefix="isegman-after-edit-")
    port = 18000 + int(time.time()) % 1000
    server = subprocess.Popen([binary, "serve", scene, "--port", str(port), "--views", "25%", "--cache", work + "/cache",
                               "--out-dir", work + "/out", "--max-seconds", "1800"],
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    base = f"http://127.0.0.1:{port}"

    def req(path, body=None):
        data = None if body is None else json.dumps(body).encode()
        r = urllib.request.Request(base + path, data=data, method="GET" if body is None else "POST",
                                   headers={"Content-Type": "application/json"})
        with urllib.request.urlopen(r, timeout=1800) as f:
            return json.loads(f.read())

    def wait_job(job):
        while True:
            s = req(f"/api/jobs/{job}")
            if s["state"] in ("done", "failed"):
                return s
            time.sleep(0.1)

    try:
        for _ in range(300):
            try:
                req("/api/status")
                break
            except OSError:
                time.sleep(0.2)
        while True:
            s = req("/api/status")
            if not s["busy"] and s["segmentation"]["state"] in ("ready", "error", "off"):
                break
            time.sleep(0.2)
        cam = req("/api/scene")["cameras"][0]
        w, h = cam["width"], cam["height"]
        t = time.time()
        wait_job(req("/api/click", {"view": 0, "x": 0.5 * w, "y": 0.45 * h, "label": 1})["job"])
        first = time.time() - t
        if scenario == "remove-object":
            req("/api/edit/remove", {})
        else:
            req("/api/select/rect", {"view": 0, "points": [[0, 0], [0.08 * w, h]]})
            req("/api/edit/colorize", {"color": "#ff0000"})
        time.sleep(pause)
        t = time.time()
        done = wait_job(req("/api/click", {"view": 0, "x": 0.7 * w, "y": 0.6 * h, "label": 1})["job"])
        after = time.time() - t
        log = [e["text"] for e in req("/api/status")["log"] if "view" in e["text"]]
        print(json.dumps({"scenario": scenario, "pause_s": pause, "first_click_s": round(first, 2),
                          "click_after_edit_s": round(after, 2), "state": done["state"], "log": log[:4]}))
    finally:
        server.terminate()
        server.wait()
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
