"""``pge view``: serve the viewer page for one recording on 127.0.0.1.

A ``ThreadingHTTPServer`` from the standard library hands out four things:
``/`` (the page), ``/viewer.js``, ``/viewer.css`` and ``/data.json`` (the
recording, converted once when the server starts). It binds the loopback
interface only, so nothing outside this machine can reach it.
"""

from __future__ import annotations

import gzip
import threading
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer

from pge.viewer.data import recording_data, to_json
from pge.viewer.page import ASSETS, asset, served_page

__all__ = ["ViewerServer", "HOST"]

HOST = "127.0.0.1"


class ViewerServer:
    """Serve ``recording`` (a ``pge.recording.Recording``) on ``HOST``.

    ``port=0`` picks a free port. ``url`` is the page's address once made;
    ``serve_forever()`` blocks (Ctrl-C ends it), ``start()`` serves from a
    daemon thread (for tests and notebooks) and ``close()`` stops either.
    """

    def __init__(self, recording, port: int = 0, start=None, end=None) -> None:
        if not 0 <= int(port) <= 65535:
            raise ValueError(f"port must be between 0 and 65535, got {port}")
        data = recording_data(recording, start, end)
        body = to_json(data).encode("utf-8")
        # built once: every request is a lookup, so the threads share nothing that changes
        self._files = {
            "/": (served_page(data["title"]).encode("utf-8"), "text/html; charset=utf-8"),
            "/data.json": (body, "application/json"),
            "/data.json.gz": (gzip.compress(body, 6), "application/json"),
        }
        for name, kind in ASSETS.items():
            self._files["/" + name] = (asset(name).encode("utf-8"), kind)
        self._files["/index.html"] = self._files["/"]
        self.httpd = ThreadingHTTPServer((HOST, int(port)), self._handler())
        self.httpd.daemon_threads = True
        self._thread = None

    @property
    def port(self) -> int:
        """The port served on."""
        return self.httpd.server_address[1]

    @property
    def url(self) -> str:
        """The page's address."""
        return f"http://{HOST}:{self.port}/"

    def _handler(self):
        files = self._files

        class Handler(BaseHTTPRequestHandler):
            def do_GET(self):  # noqa: N802 (the name http.server calls)
                path = self.path.split("?", 1)[0].split("#", 1)[0]
                found = files.get(path)
                if found is None:
                    self.send_error(404, "not part of the pge viewer")
                    return
                body, kind = found
                zipped = path == "/data.json" and "gzip" in self.headers.get("Accept-Encoding", "")
                if zipped:
                    body = files["/data.json.gz"][0]
                self.send_response(200)
                self.send_header("Content-Type", kind)
                self.send_header("Content-Length", str(len(body)))
                self.send_header("Cache-Control", "no-store")
                if zipped:
                    self.send_header("Content-Encoding", "gzip")
                self.end_headers()
                self.wfile.write(body)

            def log_message(self, format, *args):  # a quiet server: the terminal shows only the URL
                pass

        return Handler

    def serve_forever(self) -> None:
        """Serve until ``close()`` or Ctrl-C (KeyboardInterrupt propagates after closing)."""
        try:
            self.httpd.serve_forever(poll_interval=0.2)
        finally:
            self.httpd.server_close()

    def start(self) -> "ViewerServer":
        """Serve from a daemon thread; returns self."""
        self._thread = threading.Thread(target=self.httpd.serve_forever, kwargs={"poll_interval": 0.1}, daemon=True)
        self._thread.start()
        return self

    def close(self) -> None:
        """Stop serving and release the port."""
        if self._thread is not None:
            self.httpd.shutdown()
            self._thread.join()
            self._thread = None
        self.httpd.server_close()

    def __enter__(self):
        return self

    def __exit__(self, *exc) -> None:
        self.close()
