#!/usr/bin/env python3
"""Runs docs/tutorial.md as a reader would and checks that every output it shows is what the commands print.

usage: tutorial.py TUTORIAL.md BIN_DIR DOMAINS_DIR

- A code block preceded by `<!-- file: NAME -->` is written to NAME in a fresh folder; `<!-- append: NAME -->`
  appends it. At the end, every file the tutorial wrote must equal the shipped domains/coffee/ file of that name,
  so the tutorial and the example cannot drift apart.
- A ```console block holds commands (`$ ...`, run with bash in that folder, BIN_DIR first on PATH) each followed
  by the output it must print (stdout and stderr). In an expected line, `{...}` matches any text; a line `...`
  matches any number of lines. A command's exit code must be 0, except the last command of a block preceded by
  `<!-- exit: N -->`, which must exit N.
"""

import os
import re
import shutil
import subprocess
import sys
import tempfile


def blocks(text):
    """(directive, language, body) for each fenced block, the directive being the HTML comment just above it."""
    lines = text.split("\n")
    i = 0
    directive = None
    while i < len(lines):
        line = lines[i]
        m = re.match(r"^<!-- (file|append|exit): (\S+) -->$", line.strip())
        if m:
            directive = (m.group(1), m.group(2))
            i += 1
            continue
        if line.startswith("```"):
            lang = line[3:].strip()
            body = []
            i += 1
            while i < len(lines) and not lines[i].startswith("```"):
                body.append(lines[i])
                i += 1
            yield directive, lang, body
            directive = None
        elif line.strip():
            directive = None if not line.startswith("<!--") else directive
        i += 1


def matches(expected, actual):
    """Whether the actual lines fit the expected ones (`...` lines, `{...}` inside a line)."""
    if not expected:
        return not actual
    if expected[0] == "...":
        return any(matches(expected[1:], actual[k:]) for k in range(len(actual) + 1))
    if not actual:
        return False
    pattern = "^" + ".*".join(re.escape(part) for part in expected[0].split("{...}")) + "$"
    return re.match(pattern, actual[0]) is not None and matches(expected[1:], actual[1:])


def main():
    tutorial, bindir, domains = sys.argv[1], os.path.abspath(sys.argv[2]), os.path.abspath(sys.argv[3])
    work = tempfile.mkdtemp(prefix="cbtl-tutorial-")
    env = dict(os.environ, PATH=bindir + os.pathsep + os.environ.get("PATH", ""), NO_COLOR="1")
    failures = 0
    written = set()
    commands = 0
    try:
        for directive, lang, body in blocks(open(tutorial).read()):
            if directive and directive[0] in ("file", "append"):
                path = os.path.join(work, directive[1])
                with open(path, "w" if directive[0] == "file" else "a") as f:
                    f.write("\n".join(body) + "\n")
                written.add(directive[1])
                continue
            if lang != "console":
                continue
            want_exit = int(directive[1]) if directive and directive[0] == "exit" else 0
            entries = []
            for line in body:
                if line.startswith("$ "):
                    entries.append((line[2:], []))
                elif entries:
                    entries[-1][1].append(line)
            for index, (command, expected) in enumerate(entries):
                commands += 1
                wanted = want_exit if index == len(entries) - 1 else 0
                run = subprocess.run(["bash", "-c", command], cwd=work, env=env, stdout=subprocess.PIPE,
                                     stderr=subprocess.STDOUT, text=True, timeout=300)
                actual = run.stdout.rstrip("\n").split("\n") if run.stdout.strip() else []
                while expected and not expected[-1].strip():
                    expected.pop()
                if run.returncode != wanted or not matches(expected, actual):
                    failures += 1
                    print("FAIL: $ %s (exit %d, wanted %d)" % (command, run.returncode, wanted))
                    print("--- the tutorial shows:\n" + "\n".join(expected))
                    print("--- the command printed:\n" + "\n".join(actual))
                else:
                    print("ok: $ " + command)
        for name in sorted(written):
            shipped = os.path.join(domains, "coffee", name)
            if not os.path.exists(shipped) or open(shipped).read() != open(os.path.join(work, name)).read():
                failures += 1
                print("FAIL: the tutorial's %s differs from %s" % (name, shipped))
    finally:
        shutil.rmtree(work, ignore_errors=True)
    print("tutorial: %d commands, %d failure(s)" % (commands, failures))
    sys.exit(1 if failures or commands == 0 else 0)


if __name__ == "__main__":
    main()
