#!/usr/bin/env python3
"""Serve a directory like `python3 -m http.server`, plus the headers of its
`_headers` file.

`_headers` is the file Netlify and Cloudflare Pages read: a path pattern on
its own line, then indented `Name: value` lines. This server applies the
`/*` section to every response, so `make serve` on dist/ and the e2e tests
run the page under the same headers (the CSP with Trusted Types, nosniff)
a static host would send.

Usage: static_server.py PORT DIR   (PORT 0 picks a free port)
"""
import functools
import http.server
import os
import sys


def read_headers(directory):
    """The `/*` section of DIR/_headers as (name, value) pairs ([] if none)."""
    path = os.path.join(directory, "_headers")
    if not os.path.exists(path):
        return []
    pairs, section = [], None
    with open(path, encoding="utf-8") as f:
        for lineno, line in enumerate(f, 1):
            if not line.strip() or line.lstrip().startswith("#"):
                continue
            if not line[0].isspace():
                section = line.strip()
                continue
            name, sep, value = line.strip().partition(":")
            if not sep or not name.strip():
                sys.exit(f"error: {path}:{lineno}: expected 'Name: value', got {line.strip()!r}")
            if section == "/*":
                pairs.append((name.strip(), value.strip()))
    return pairs


class Handler(http.server.SimpleHTTPRequestHandler):
    extra = []

    def end_headers(self):
        for name, value in self.extra:
            self.send_header(name, value)
        super().end_headers()


def main():
    if len(sys.argv) != 3 or not sys.argv[1].isdigit() or not 0 <= int(sys.argv[1]) <= 65535:
        sys.exit("usage: static_server.py PORT DIR  (PORT an integer in 0..=65535)")
    port, directory = int(sys.argv[1]), sys.argv[2]
    if not os.path.isdir(directory):
        sys.exit(f"error: {directory} is not a directory")
    Handler.extra = read_headers(directory)
    Handler.extensions_map = {**Handler.extensions_map, ".wasm": "application/wasm", ".mjs": "text/javascript", ".js": "text/javascript"}
    handler = functools.partial(Handler, directory=directory)
    with http.server.ThreadingHTTPServer(("127.0.0.1", port), handler) as httpd:
        host, real_port = httpd.server_address[:2]
        print(f"Serving HTTP on {host} port {real_port} (http://{host}:{real_port}/) ...", flush=True)
        try:
            httpd.serve_forever()
        except KeyboardInterrupt:
            pass


if __name__ == "__main__":
    main()
