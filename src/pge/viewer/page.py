"""The viewer page: one HTML template, filled either for the server or as a single file.

The template, script and style sheet are package data (``pge/viewer/static``),
so the page needs nothing from the internet. ``served_page`` links the script
and style sheet and loads the recording from ``data.json``;
``standalone_page`` inlines all three, for ``pge export FILE out.html`` and
for notebooks.
"""

from __future__ import annotations

import html
from importlib import resources

from pge.viewer.data import to_json

__all__ = ["asset", "served_page", "standalone_page", "ASSETS"]

#: files the server hands out besides the page, with their content types.
ASSETS = {"viewer.js": "text/javascript; charset=utf-8", "viewer.css": "text/css; charset=utf-8"}


def asset(name: str) -> str:
    """The text of the packaged file ``static/name``."""
    return resources.files("pge.viewer").joinpath("static", name).read_text(encoding="utf-8")


def _fill(title: str, style: str, script: str, data_src: str, data: str) -> str:
    page = asset("viewer.html")
    # the data goes in last: a recording's text must never be taken for a placeholder
    for key, value in (
        ("__PGE_TITLE__", html.escape(title)),
        ("__PGE_STYLE__", style),
        ("__PGE_SCRIPT__", script),
        ("__PGE_DATA_SRC__", html.escape(data_src)),
    ):
        page = page.replace(key, value)
    return page.replace("__PGE_DATA__", data)


def served_page(title: str) -> str:
    """The page ``pge view`` serves: script, style and data as separate requests."""
    return _fill(
        title,
        '<link rel="stylesheet" href="viewer.css">',
        '<script src="viewer.js"></script>',
        "data.json",
        "",
    )


def standalone_page(data: dict) -> str:
    """One self-contained HTML document playing ``data`` (from ``recording_data``)."""
    # "</" cannot occur in the script or style we ship, so inlining them cannot end their elements early
    script = asset("viewer.js")
    style = asset("viewer.css")
    return _fill(
        data.get("title", "recording"),
        f"<style>\n{style}</style>",
        f"<script>\n{script}</script>",
        "",
        to_json(data, for_script=True),
    )
