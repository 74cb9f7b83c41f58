#!/usr/bin/env python3
"""Serves a web build (`web/build.sh`'s folder) on 127.0.0.1, compressed.

    python3 web/serve.py [DIR] [--port 8000]

A file with a `.br` or `.gz` beside it (build.sh writes both for `showcase_bg.wasm` and
`showcase.js`) is sent as the smaller one the browser accepts (`Accept-Encoding`), with its
`Content-Encoding`: a visitor downloads the compressed size. `.wasm` goes out as `application/wasm`, so browsers compile it as it arrives.
Python's standard library only; `python3 -m http.server` works too, but sends the uncompressed
files.
"""
import argparse
import functools
import http.server
import os

TYPES = {".wasm": "application/wasm", ".js": "text/javascript", ".html": "text/html"}


class Handler(http.server.SimpleHTTPRequestHandler):
    extensions_map = {**http.server.SimpleHTTPRequestHandler.extensions_map, **TYPES}

    def send_head(self):
        path = self.translate_path(self.path)
        accepts = self.headers.get("Accept-Encoding", "")
        found = [(encoding, path + suffix) for encoding, suffix in (("br", ".br"), ("gzip", ".gz"))
                 if encoding in accepts and os.path.isfile(path + suffix)]
        if not (found and os.path.isfile(path)):
            return super().send_head()
        encoding, packed = found[0]
        body = open(packed, "rb")
        self.send_response(200)
        self.send_header("Content-Type", self.guess_type(path))
        self.send_header("Content-Encoding", encoding)
        self.send_header("Content-Length", str(os.fstat(body.fileno()).st_size))
        self.send_header("Vary", "Accept-Encoding")
        self.end_headers()
        return body

    def log_message(self, *args):
        pass  # quiet


def server(directory, port=0):
    """A threading server for `directory` on 127.0.0.1 (port 0: any free port)."""
    handler = functools.partial(Handler, directory=directory)
    return http.server.ThreadingHTTPServer(("127.0.0.1", port), handler)


def main():
    default = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "target", "web", "webgl2")
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("dir", nargs="?", default=default)
    ap.add_argument("--port", type=int, default=8000)
    args = ap.parse_args()
    httpd = server(args.dir, args.port)
    print(f"serving {os.path.normpath(args.dir)} at http://127.0.0.1:{httpd.server_address[1]}/")
    try:
        httpd.serve_forever()
    except KeyboardInterrupt:
        pass


if __name__ == "__main__":
    main()
