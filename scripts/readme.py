#!/usr/bin/env python3
"""Runs every shell and Python block of a Markdown guide as written, as a reader would.

Usage: scripts/readme.py [README.md] [--python-only] [--folder DIR] [--list]

The fenced blocks marked ``sh`` run in order in one bash session started in the guide's folder
(so an ``export`` or ``. .venv/bin/activate`` in one block holds for the next, as in a reader's
terminal), with ``set -euo pipefail``; a ``python`` block runs in that session as ``python3`` with
the block on its standard input. An HTML comment on the line before a block changes how it runs:

  <!-- readme-test: skip (REASON) -->   not run; the reason is printed (CI runs it another way)
  <!-- readme-test: serve URL -->       the block's last command starts a server: the commands
                                        before it run as usual, the server runs in the background
                                        until URL answers 200 (at most 120 s), then it is stopped

With --python-only only the Python blocks run (docs/guide.md, whose shell blocks are templates
naming the reader's own files); --folder sets the folder they run in (default: the guide's).
Any failing command fails the whole run (exit status 1) and names the block and its line. CI runs
this on a fresh clone (`.ci/run`), so every example in the README runs there as written.
"""

import argparse
import os
import re
import shlex
import subprocess
import sys

FENCE = re.compile(r"^```(\w*)\s*$")
MARK = re.compile(r"^<!--\s*readme-test:\s*(skip|serve)\s*(.*?)\s*-->\s*$")


def blocks(text):
    """(language, first line number, code, mark, argument) of each fenced block."""
    found, lines, i, mark = [], text.split("\n"), 0, (None, "")
    while i < len(lines):
        marked = MARK.match(lines[i])
        opened = FENCE.match(lines[i])
        if marked:
            mark = (marked.group(1), marked.group(2))
        elif opened:
            language, start, body = opened.group(1), i + 2, []
            i += 1
            while i < len(lines) and not lines[i].startswith("```"):
                body.append(lines[i])
                i += 1
            found.append((language, start, "\n".join(body) + "\n", mark[0], mark[1]))
            mark = (None, "")
        elif lines[i].strip():
            mark = (None, "")
        i += 1
    return found


def serve_script(code, url):
    """The block's last command is a server: the commands before it run as usual, then the server
    runs in the background until `url` answers 200, and is stopped."""
    lines = code.rstrip("\n").split("\n")
    server = lines.pop()
    probe = "import sys, urllib.request; sys.exit(urllib.request.urlopen(sys.argv[1], timeout=2).status != 200)"
    return "\n".join(lines) + (
        "\nsetsid bash -c " + shlex.quote(server) + " > \"$readme_log\" 2>&1 &\n"
        "server=$!\n"
        "answered=0\n"
        "for _ in $(seq 240); do\n"
        "  if python3 -c " + shlex.quote(probe) + " " + shlex.quote(url) + " 2> /dev/null; then answered=1; break; fi\n"
        "  kill -0 $server 2> /dev/null || break\n"
        "  sleep 0.5\n"
        "done\n"
        "kill -- -$server 2> /dev/null || true\n"
        "wait $server 2> /dev/null || true\n"
        "cat \"$readme_log\"\n"
        "[ $answered = 1 ] || { echo " + shlex.quote(f"the server never answered {url}") + " >&2; false; }\n"
        "echo " + shlex.quote(f"answered: {url}") + "\n"
    )


def script(path, found, python_only=False):
    """One bash script that runs the blocks in order, announcing each."""
    name = os.path.basename(path)
    parts = ["set -euo pipefail", "readme_log=$(mktemp)", "trap 'rm -f \"$readme_log\"' EXIT"]
    for language, line, code, mark, argument in found:
        where = f"{name}:{line}"
        if language not in ("sh", "python") or (python_only and language != "python"):
            continue
        if mark == "skip":
            parts.append(f"echo {shlex.quote(f'== {where}: skipped {argument}')}")
            continue
        parts.append(f"echo {shlex.quote(f'== {where}: {language} block')} \"(at $SECONDS s)\"")
        parts.append(f"readme_block={shlex.quote(where)}")
        if mark == "serve":
            parts.append(serve_script(code, argument))
        elif language == "sh":
            parts.append(code)
        else:
            parts.append("python3 - <<'README_PYTHON_BLOCK'\n" + code + "README_PYTHON_BLOCK")
    parts.append("echo \"== every block ran ($SECONDS s)\"")
    return "\n".join(parts) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("guide", nargs="?", default="README.md")
    parser.add_argument("--python-only", action="store_true", help="run only the Python blocks")
    parser.add_argument("--folder", help="the folder the blocks run in (default: the guide's)")
    parser.add_argument("--list", action="store_true", help="print the script instead of running it")
    args = parser.parse_args()
    with open(args.guide, encoding="utf-8") as handle:
        found = blocks(handle.read())
    text = script(args.guide, found, args.python_only)
    if args.list:
        sys.stdout.write(text)
        return 0
    folder = args.folder or os.path.dirname(os.path.abspath(args.guide))
    # On failure bash's ERR trap names the block that was running.
    text = "trap 'echo \"readme: the block at $readme_block failed (line $LINENO of the script)\" >&2' ERR\n" + text
    return subprocess.run(["bash", "-c", text], cwd=folder).returncode


if __name__ == "__main__":
    sys.exit(main())
