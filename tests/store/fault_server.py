#!/usr/bin/python3
"""A static HTTP server on 127.0.0.1 that misbehaves on purpose, for the store pull tests
(tests/cli/test_pull.py): what nginx serving a published store does not do.

    /usr/bin/python3 tests/store/fault_server.py DIRECTORY LOG

Serves DIRECTORY's files at /NAME with a strong ETag, Last-Modified and byte ranges (Range, and
If-Range compared with the ETag), on a free port it prints on stdout's first line. Faults come
from DIRECTORY/.faults (JSON, read at each request so a test can change it): {"NAME": [FAULT,
...]}, each FAULT applied to the Nth request of NAME it counts from 1:

  "close-after:N"  the first request: the headers of the full answer, N bytes, then the
                   connection closed
  "stall-after:N"  the first request: N bytes, then nothing for 30 s
  "503-once"       the first request: 503 with Retry-After: 1
  "429-once"       the first request: 429 (Too Many Requests) with Retry-After: 1
  "404"            every request: 404
  "ignore-range"   every request: the whole file with 200, whatever Range says
  "wrong-range"    every request with a Range: 206 with the whole file (Content-Range from 0)
  "html"           every request: 200 with an HTML error page, as a misconfigured host answers

Each request is appended to LOG as one line: METHOD PATH STATUS "RANGE" "IF-RANGE".
"""

import email.utils
import hashlib
import http.server
import json
import os
import socket
import sys
import threading
import time

DIRECTORY, LOG = sys.argv[1], sys.argv[2]
counts = {}
lock = threading.Lock()


class Handler(http.server.BaseHTTPRequestHandler):
    protocol_version = "HTTP/1.1"

    def log_message(self, *args):
        pass

    def record(self, status):
        with lock, open(LOG, "a") as f:
            f.write('%s %s %d "%s" "%s"\n' % (self.command, self.path, status,
                                              self.headers.get("Range", ""),
                                              self.headers.get("If-Range", "")))

    def answer(self, status, body, headers=()):
        self.record(status)
        self.send_response(status)
        for name, value in headers:
            self.send_header(name, value)
        self.send_header("Content-Length", str(len(body)))
        self.end_headers()
        self.wfile.write(body)

    def do_GET(self):
        name = self.path.lstrip("/")
        try:
            with open(os.path.join(DIRECTORY, ".faults")) as f:
                faults = json.load(f).get(name, [])
        except FileNotFoundError:
            faults = []
        with lock:
            counts[name] = counts.get(name, 0) + 1
            first = counts[name] == 1
        path = os.path.join(DIRECTORY, name)
        if "/" in name or name.startswith(".") or not os.path.isfile(path) or "404" in faults:
            return self.answer(404, b"not found\n")
        for status in (503, 429):
            if "%d-once" % status in faults and first:
                return self.answer(status, b"busy\n", [("Retry-After", "1")])
        if "html" in faults:
            return self.answer(200, b"<html><body>Quota exceeded</body></html>\n",
                               [("Content-Type", "text/html")])
        with open(path, "rb") as f:
            data = f.read()
        etag = '"%s"' % hashlib.sha256(data).hexdigest()[:16]
        modified = email.utils.formatdate(os.path.getmtime(path), usegmt=True)
        start, status = 0, 200
        wanted = self.headers.get("Range", "")
        if_range = self.headers.get("If-Range")
        if (wanted.startswith("bytes=") and wanted.endswith("-") and "ignore-range" not in faults
                and (if_range is None or if_range in (etag, modified))):
            start, status = int(wanted[6:-1]), 206
            if start >= len(data):
                return self.answer(416, b"", [("Content-Range", "bytes */%d" % len(data))])
        if "wrong-range" in faults and status == 206:
            start = 0
        body = data[start:]
        self.record(status)
        self.send_response(status)
        self.send_header("ETag", etag)
        self.send_header("Last-Modified", modified)
        self.send_header("Accept-Ranges", "bytes")
        if status == 206:
            self.send_header("Content-Range", "bytes %d-%d/%d" % (start, len(data) - 1, len(data)))
        self.send_header("Content-Length", str(len(body)))
        self.end_headers()
        for fault in faults:
            if fault.startswith("close-after:") and first:
                self.wfile.write(body[:int(fault.split(":")[1])])
                self.wfile.flush()
                self.connection.shutdown(socket.SHUT_RDWR)
                self.close_connection = True
                return
            if fault.startswith("stall-after:") and first:
                self.wfile.write(body[:int(fault.split(":")[1])])
                self.wfile.flush()
                time.sleep(30)
                self.close_connection = True
                return
        self.wfile.write(body)


class Server(http.server.ThreadingHTTPServer):
    daemon_threads = True


server = Server(("127.0.0.1", 0), Handler)
print(server.server_address[1], flush=True)
server.serve_forever()
