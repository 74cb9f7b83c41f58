#!/usr/bin/env python3
"""Open a static web build of the game in headless Chromium and collect the screenshots it saves.

On wasm, Bevy's `save_to_disk` encodes the PNG, wraps it in a Blob URL and clicks an
`<a download="NAME.png">` link: each screenshot is a browser *download*. This script serves
SITE_DIR over HTTP on 127.0.0.1 with web/serve.py (compressed), starts Chromium (headless, or with `--headed` a window for
xvfb-run; WebGPU on SwiftShader, `--webgl2` without the WebGPU flags for a WebGL2 build, or
`--gpu-flags` of your own), tells it through the Chrome
DevTools Protocol to accept downloads into OUT_DIR, opens index.html?QUERY, echoes the page's
console (also to OUT_DIR/console.log; Chromium's stderr goes to OUT_DIR/chromium.log) and waits
until every expected file has arrived (or, with --expect-notice, until the page's notice shows
the text). It also follows the page's loading indicator once a second and reports the bytes each
file took on the wire.

CDP normally speaks WebSocket, which the standard library lacks, so Chromium is started with
`--remote-debugging-pipe`: it reads commands on its fd 3 and writes replies and events on its
fd 4, each message a JSON object terminated by a NUL byte.

Usage: web.py SITE_DIR OUT_DIR [--url-query Q] (--expect A.png,B.png | --expect-notice TEXT)
              [--timeout S] [--webgl2] [--viewport WxH] [--headed] [--gpu-flags "FLAGS"]

WebGPU on SwiftShader needs Chromium's Vulkan on SwiftShader too (`--use-vulkan=swiftshader`):
without it the device is lost at the first frame a page presents to a canvas ("A valid external
Instance reference no longer exists"), headless and headed alike (docs/live.md, "Browsers").
Exit 0 once all expected files are there, the indicator showed the download and the shaders
compiling before the first frame and then the scene, and the console showed no error; 1 otherwise
(a timeout lists the missing files), or if Chromium dies.
"""
import argparse
import fcntl
import base64
import json
import os
import queue
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time

START = time.monotonic()
# Whether the page has WebGPU's object (Chromium on Linux has it even without WebGPU flags; only
# an adapter would tell, and the script does not ask for one beside the game's).
WEBGPU = "navigator.gpu ? 'navigator.gpu present' : 'no webgpu'"


def serve(site):
    """web/serve.py's server (compressed files to browsers that take them) on a free port."""
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "web"))
    import serve as web_serve
    server = web_serve.server(site)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    return server.server_address[1]


def find_chromium():
    found = [shutil.which(n) for n in ("chromium", "chromium-browser", "google-chrome")]
    return next(filter(None, found), None) or sys.exit("web.py: no chromium on PATH")


class Cdp:
    """Chromium with a DevTools pipe: send() waits for the reply, events go to self.events."""

    def __init__(self, argv, stderr):
        to_child, self.cmd = os.pipe()       # we write commands, Chromium reads fd 3
        self.resp, from_child = os.pipe()    # Chromium writes fd 4, we read

        def fds_3_and_4():                   # in the child, before exec
            r = fcntl.fcntl(to_child, fcntl.F_DUPFD, 10)  # out of the way of 3 and 4 first
            w = fcntl.fcntl(from_child, fcntl.F_DUPFD, 10)
            os.dup2(r, 3)                    # dup2 makes 3 and 4 inheritable: they survive exec
            os.dup2(w, 4)

        # close_fds=False rather than pass_fds=(3, 4): pass_fds needs 3 and 4 open in this
        # process too. Nothing else leaks: Python opens every other file non-inheritable.
        self.proc = subprocess.Popen(argv, preexec_fn=fds_3_and_4, close_fds=False,
                                     start_new_session=True,  # its own process group
                                     stdout=stderr, stderr=stderr)
        for fd in (to_child, from_child):
            os.close(fd)
        self.next_id, self.waiting, self.lock, self.events = 0, {}, threading.Lock(), queue.Queue()
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self):
        buf = b""
        while chunk := os.read(self.resp, 1 << 16):
            *messages, buf = (buf + chunk).split(b"\0")
            for raw in messages:
                msg = json.loads(raw)
                (self.waiting.pop(msg["id"]) if "id" in msg else self.events).put(msg)
        self.events.put({"method": "closed"})

    def send(self, method, params=None, session=None, timeout=30):
        with self.lock:
            self.next_id += 1
            msg = {"id": self.next_id, "method": method, "params": params or {}}
            if session:
                msg["sessionId"] = session
            reply = self.waiting[self.next_id] = queue.Queue()
            os.write(self.cmd, json.dumps(msg).encode() + b"\0")
        try:
            msg = reply.get(timeout=timeout)
        except queue.Empty:
            raise RuntimeError("no reply to %s within %ss" % (method, timeout))
        if "error" in msg:
            raise RuntimeError("%s: %s" % (method, msg["error"]))
        return msg["result"]

    def close(self):
        """Browser.close, then SIGKILL to Chromium's process group if it lingers."""
        if self.proc.returncode is not None:  # already gone (and reaped)
            return
        try:
            self.send("Browser.close", timeout=5)
            self.proc.wait(timeout=10)
        except (OSError, RuntimeError, subprocess.TimeoutExpired):
            os.killpg(self.proc.pid, signal.SIGKILL)  # not reaped yet, so the group is still ours
            self.proc.wait()


def remote_text(obj):
    """A console argument (a CDP RemoteObject) as text."""
    if "value" not in obj:
        return obj.get("description") or obj.get("unserializableValue") or obj["type"]
    return obj["value"] if isinstance(obj["value"], str) else json.dumps(obj["value"])


def console_line(event):
    """The text of a console/exception/log event, or None for other events."""
    method, p = event.get("method"), event.get("params", {})
    if method == "Runtime.consoleAPICalled":
        return "console.%s: %s" % (p["type"], " ".join(remote_text(a) for a in p["args"]))
    if method == "Runtime.exceptionThrown":
        d = p["exceptionDetails"]
        return "exception: %s" % (d.get("exception", {}).get("description") or d.get("text"))
    if method == "Log.entryAdded":
        e = p["entry"]
        return "log.%s: %s %s" % (e["level"], e["text"], e.get("url", ""))
    return None


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("site")
    ap.add_argument("out")
    ap.add_argument("--url-query", default="")
    ap.add_argument("--expect", default="", help="comma-separated file names")
    ap.add_argument("--expect-notice", default=None,
                    help="wait for the page's notice to show this text instead of files")
    ap.add_argument("--expect-console", default=None,
                    help="also wait for a console line with this text (the tour's fingerprint)")
    ap.add_argument("--timeout", type=float, default=600, help="seconds")
    ap.add_argument("--webgl2", action="store_true", help="no WebGPU flags: WebGL2 fallback")
    ap.add_argument("--viewport", default="640x360", help="the page's size, WxH")
    ap.add_argument("--gpu-flags", default=None, help="Chromium's GPU flags instead of ours")
    ap.add_argument("--headed", action="store_true",
                    help="a window (run under xvfb-run) instead of headless")
    args = ap.parse_args()
    site, out = os.path.abspath(args.site), os.path.abspath(args.out)
    expected = [name for name in args.expect.split(",") if name]
    if not expected and args.expect_notice is None:
        sys.exit("web.py: --expect FILES or --expect-notice TEXT")
    os.makedirs(out, exist_ok=True)
    for name in set(expected) & set(os.listdir(out)):  # a stale copy would count as arrived,
        os.remove(os.path.join(out, name))           # and the new one would be "NAME (1).png"
    log = open(os.path.join(out, "console.log"), "w")

    def say(text):
        line = "[%7.1fs] %s" % (time.monotonic() - START, text[:300])
        print(line, flush=True)
        print(line, file=log, flush=True)

    profile = tempfile.mkdtemp(prefix="web-chromium-")
    flags = ([] if args.headed else ["--headless=new"]) + ["--no-sandbox", "--enable-unsafe-swiftshader",
             "--window-size=640,360", "--remote-debugging-pipe", "--user-data-dir=" + profile,
             "--no-first-run", "--no-default-browser-check"]
    if args.gpu_flags is not None:
        flags += args.gpu_flags.split()
    elif not args.webgl2:
        flags += ["--enable-unsafe-webgpu", "--use-webgpu-adapter=swiftshader",
                  "--enable-features=Vulkan", "--use-vulkan=swiftshader",
                  "--use-angle=swiftshader", "--ignore-gpu-blocklist"]
    stderr = open(os.path.join(out, "chromium.log"), "w")  # Chromium's own complaints (GPU...)
    browser = Cdp([find_chromium()] + flags + ["about:blank"], stderr)  # before any thread
    port = serve(site)
    try:
        sys.exit(run(browser, port, out, expected, args, say))
    finally:
        browser.close()
        shutil.rmtree(profile, ignore_errors=True)


# The page's loading indicator and notice, as one line of text.
PAGE_STATE = """(() => {
  const loading = document.getElementById('loading'), notice = document.getElementById('notice');
  return (loading && !loading.hidden ? 'loading: ' + document.getElementById('status').textContent
          : 'drawing') + (notice && !notice.hidden ? ' | notice: ' + notice.textContent : '');
})()"""


def run(browser, port, out, expected, args, say):
    browser.send("Browser.setDownloadBehavior",
                 {"behavior": "allow", "downloadPath": out, "eventsEnabled": True})
    target = browser.send("Target.createTarget", {"url": "about:blank"})["targetId"]
    session = browser.send("Target.attachToTarget",
                           {"targetId": target, "flatten": True})["sessionId"]
    for domain in ("Runtime", "Log", "Page", "Network"):
        browser.send(domain + ".enable", session=session)
    # The page's viewport, as the native examples' window (--window-size counts the browser's
    # frame too).
    width, height = (int(v) for v in args.viewport.split("x"))
    browser.send("Emulation.setDeviceMetricsOverride", {"width": width, "height": height,
                 "deviceScaleFactor": 1, "mobile": False}, session=session)

    def evaluate(expression, timeout=10):  # a busy page may not answer: not the end of the wait
        try:
            result = browser.send("Runtime.evaluate", {"expression": expression,
                                  "awaitPromise": True}, session=session, timeout=timeout)["result"]
            return remote_text(result)
        except (OSError, RuntimeError) as e:
            return "(no answer: %s)" % e

    def page_png(name):  # the whole page (the canvas, the indicator, the notice) as the user sees it
        try:
            data = browser.send("Page.captureScreenshot", {"format": "png"}, session=session)["data"]
            open(os.path.join(out, name), "wb").write(base64.b64decode(data))
            say("page screenshot: %s" % name)
        except (OSError, RuntimeError) as e:
            say("no page screenshot %s: %s" % (name, e))

    url = "http://127.0.0.1:%d/index.html" % port + ("?" + args.url_query) * bool(args.url_query)
    say("chromium %s, opening %s" % (browser.send("Browser.getVersion")["product"], url))
    browser.send("Page.navigate", {"url": url}, session=session)

    names = {}          # download guid -> suggested file name
    completed = set()   # file names whose download Chromium reports completed
    sizes = {}          # file name -> (size, since when), for a download without events
    requests = {}       # request id -> url, for the bytes each file took on the wire
    errors = []         # console errors and exceptions: a clean page has none
    console_seen = args.expect_console is None  # the console line waited for, if any
    states = []         # the indicator's states in order ("loading: ...", "drawing")
    deadline, next_report, next_state = START + args.timeout, time.monotonic() + 30, 0
    while True:
        try:
            event = browser.events.get(timeout=0.5)
        except queue.Empty:
            event = {}  # no event: still check the folder, the clock and Chromium
        method, p = event.get("method"), event.get("params", {})
        if (line := console_line(event)) is not None:
            say(line)
            if args.expect_console is not None and args.expect_console in line:
                console_seen = True
            if line.startswith(("exception:", "console.error:", "log.error:")):
                errors.append(line)
        elif method == "Page.loadEventFired" and event.get("sessionId") == session:
            say("loaded; %s; webgl2 context: %s" % (evaluate(WEBGPU), evaluate(
                "!!document.createElement('canvas').getContext('webgl2')")))
        elif method == "Network.requestWillBeSent":
            requests[p["requestId"]] = p["request"]["url"].split("?")[0].rsplit("/", 1)[-1]
        elif method == "Network.loadingFinished" and p["requestId"] in requests:
            say("fetched %s: %d bytes on the wire" % (requests[p["requestId"]],
                                                      p["encodedDataLength"]))
        elif method == "Browser.downloadWillBegin":
            names[p["guid"]] = p["suggestedFilename"]
            say("download begins: %s (page: %s)" % (p["suggestedFilename"], states[-1:] or "?"))
        elif method == "Browser.downloadProgress" and p["state"] != "inProgress":
            name = names.get(p["guid"], p["guid"])
            say("download %s: %s (%d bytes)" % (p["state"], name, p.get("receivedBytes", 0)))
            if p["state"] == "completed":
                if os.path.exists(os.path.join(out, p["guid"])):  # saved under its guid: rename
                    os.replace(os.path.join(out, p["guid"]), os.path.join(out, name))
                completed.add(name)
        elif method == "closed" or browser.proc.poll() is not None:
            say("FAIL: chromium exited (code %s)" % browser.proc.poll())
            return 1

        now = time.monotonic()
        if now >= next_state:  # the indicator, once a second: each new state logged, once
            next_state = now + 1
            state = evaluate(PAGE_STATE, timeout=5)
            if not state.startswith("(no answer") and (not states or states[-1] != state):
                states.append(state)
                say("page: %s" % state)
                if state.startswith("loading: compiling") and not any(
                        s.startswith("loading: compiling") for s in states[:-1]):
                    page_png("page_compiling.png")
        partial = any(f.endswith(".crdownload") for f in os.listdir(out))
        done = []
        for n in (n for n in expected if os.path.exists(os.path.join(out, n))):
            size = os.path.getsize(os.path.join(out, n))
            if sizes.get(n, (None,))[0] != size:
                sizes[n] = (size, now)
            stable = size > 0 and now - sizes[n][1] > 2 and not partial
            if n in completed or stable:
                done.append(n)
        notice = args.expect_notice is not None and any(
            "notice: " in s and args.expect_notice in s.split("notice: ", 1)[1] for s in states)
        if (expected and len(done) == len(expected) and console_seen) or notice:
            if notice:
                time.sleep(1)
                page_png("page_notice.png")
            say("done: %s" % (", ".join(done) or "the notice is shown"))
            log = evaluate("JSON.stringify(window.loadingLog.map(e => e.shown))", timeout=10)
            say("the indicator showed, in order: %s" % log)
            try:
                shown = json.loads(log)
            except ValueError:
                shown = []
            return verdict(shown, errors, say)
        if now >= deadline:
            say("FAIL: timeout after %ss; missing %s (have %s); page title %r" % (
                args.timeout, ", ".join(n for n in expected if n not in done),
                ", ".join(done) or "nothing", evaluate("document.title")))
            return 1
        if now >= next_report:
            next_report = now + 30
            title = evaluate("document.title")
            say("waiting: have [%s], page title %r" % (", ".join(done), title))
            # The page (web/index.html) puts an uncaught error or a panic in its title.
            if isinstance(title, str) and title.startswith("error"):
                say("FAIL: the page failed: %s" % title)
                return 1


def verdict(shown, errors, say):
    """The page's checks once the run is done: the loading indicator (as the page recorded it,
    `window.loadingLog`) showed the download and the shaders compiling before the first frame,
    then gave way to the scene; no console errors."""
    failures = list(errors)
    first_drawn = next((i for i, s in enumerate(shown) if s == "scene"), None)
    before = shown[:first_drawn]
    if "downloading" not in before:
        failures.append("the indicator never showed the download before the first frame")
    if "compiling" not in before:
        failures.append("the indicator never said it was compiling shaders before the first frame")
    if first_drawn is None:
        failures.append("the indicator never gave way to the scene")
    for failure in failures:
        say("FAIL: %s" % failure)
    return 1 if failures else 0


if __name__ == "__main__":
    main()
