#!/usr/bin/env python3
"""Runs the user commands documented in README.md and docs/**/*.md, as a user would.

The commands run in a copy of the project with nothing next to it, as a user's clone has it, with
the build's `wrc` first in PATH, and each must exit with 0. What runs:

- fenced blocks marked ```sh, ```bash or ```console, except those marked `no-run` after the
  language (```sh no-run: builds, installs, fuzzing, commands that need test data);
- in them, the commands of a user of wrc: `wrc ...`, `build/...` programs (but not the test
  programs of build/tests), and `python3` with PYTHONPATH=build/python; set-up commands
  (cmake, bash tools/...) are left to tools/test.sh;
- a line with the comment `# not run` is left out and listed.

Placeholders run on small stand-ins, and long jobs on a small equivalent (listed in
STAND_INS): a 40-minute table on the 27-point demo scene, 1000 verify samples on 6, an
error map of 31 × 31 solves on 5 × 5, a dynamics study's linearised contact in place of its
minutes of solver-driven runs (those are checked in tests/studies/dynamics).

usage: documented_commands.py SOURCE_DIR BUILD_DIR [PYTHON]

PYTHON is the interpreter the Python module was built for; its directory comes first in PATH,
so that `python3` in the documents is that one (on Debian, /usr/bin/python3).
"""

import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile

DOCUMENTS = ["README.md"]
LANGUAGES = {"sh", "bash", "console"}
# (pattern, replacement), applied in order to every command that runs.
STAND_INS = [
    (r"\btables/(mbench|heavy_haul)\.toml\b", "tables/demo.toml"),  # 40 / 12 min -> seconds
    (r"\b(mbench|heavy_haul)\.h5\b", "demo-table.h5"),
    (r"--samples [0-9]{3,}", "--samples 6"),
    (r"\by_wheel\b", "y"),  # the demo scene's lateral axis
    (r"(--map \S+)", r"\1 --map-size 5"),  # 25 exact solves instead of 961
    (r"(\bstudy dynamics \S+)", r"\1 --linear-only"),  # 10 min of full solves -> seconds
    (r"(?<![\w/.])SCENE\.toml\b", "tables/demo.toml"),
    (r"(?<![\w/.])CASE(\.toml)?\b", "tables/mbench_case.toml"),
    (r"(?<![\w/.])TABLE\.h5\b", "demo-table.h5"),
    (r"(?<![\w/.])DIR\b", "out-dir"),
]
BLOCK_TIMEOUT_S = 600


def documents(source):
    found = [os.path.join(source, d) for d in DOCUMENTS]
    for root, _, files in os.walk(os.path.join(source, "docs")):
        found += [os.path.join(root, f) for f in sorted(files) if f.endswith(".md")]
    return sorted(p for p in found if os.path.isfile(p))


def blocks(path):
    """Yields (first line number, [logical lines]) of each runnable fenced block."""
    lines = open(path, encoding="utf-8").read().split("\n")
    k = 0
    while k < len(lines):
        fence = re.match(r"^(```+)\s*(\S*)(.*)$", lines[k])
        if not fence:
            k += 1
            continue
        start, body = k + 1, []
        k += 1
        while k < len(lines) and not lines[k].startswith(fence.group(1)):
            body.append(lines[k])
            k += 1
        k += 1
        if fence.group(2) in LANGUAGES and "no-run" not in fence.group(3):
            yield start + 1, logical_lines(body)


def logical_lines(body):
    joined, current = [], ""
    for line in body:
        if line.endswith("\\"):
            current += line[:-1] + " "
            continue
        joined.append(current + line)
        current = ""
    return [re.sub(r"^\$ ", "", line.strip()) for line in joined]


def is_user_command(line):
    try:
        words = shlex.split(line, comments=True)
    except ValueError:
        return False
    env = [w for w in words if re.match(r"^[A-Z_]+=", w)]
    words = words[len(env):] if words[: len(env)] == env else words
    if not words:
        return False
    program = words[0]
    if program == "wrc":
        return True
    if program.startswith("build/") and not program.startswith("build/tests/"):
        return True
    return program == "python3" and any(e.startswith("PYTHONPATH=build/python") for e in env)


def stand_in(line):
    for pattern, replacement in STAND_INS:
        line = re.sub(pattern, replacement, line)
    return line


def copy_project(source, target):
    """The files a user's copy has: git's files when this is a checkout, else all but builds."""
    listed = subprocess.run(
        ["git", "-C", source, "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
        capture_output=True,
    )
    if listed.returncode == 0 and listed.stdout:
        for name in listed.stdout.decode().split("\0"):
            if name and os.path.isfile(os.path.join(source, name)):
                os.makedirs(os.path.dirname(os.path.join(target, name)), exist_ok=True)
                shutil.copy2(os.path.join(source, name), os.path.join(target, name))
    else:
        shutil.copytree(source, target, ignore=shutil.ignore_patterns("build*", ".git"))


def run_block(script, cwd, env):
    return subprocess.run(
        ["bash", "-e", "-o", "pipefail", "-c", script],
        cwd=cwd,
        env=env,
        capture_output=True,
        text=True,
        timeout=BLOCK_TIMEOUT_S,
    )


def main():
    source, build = (os.path.abspath(a) for a in sys.argv[1:3])
    python_dir = [os.path.dirname(sys.argv[3])] if len(sys.argv) > 3 and sys.argv[3] else []
    work = tempfile.mkdtemp(prefix="wrc-docs-")
    try:
        copy = os.path.join(work, "wrc")  # nothing else in `work`
        copy_project(source, copy)
        os.symlink(build, os.path.join(copy, "build"))
        env = dict(os.environ, PATH=os.pathsep.join([build] + python_dir + [os.environ["PATH"]]))
        # The table that TABLE.h5 stands for.
        prelude = run_block("wrc generate tables/demo.toml -o demo-table.h5 --quiet", copy, env)
        if prelude.returncode != 0:
            print(prelude.stderr)
            return 1
        failures, ran, skipped = 0, 0, []
        for path in documents(copy):
            name = os.path.relpath(path, copy)
            for line_number, lines in blocks(path):
                commands = []
                for line in lines:
                    if not is_user_command(line):
                        continue
                    if "# not run" in line:
                        skipped.append(f"{name}:{line_number}: {line}")
                        continue
                    commands.append(stand_in(line))
                if not commands:
                    continue
                result = run_block("\n".join(commands), copy, env)
                ran += len(commands)
                status = "ok" if result.returncode == 0 else f"FAILED (exit {result.returncode})"
                print(f"{name}:{line_number}: {status}")
                for command in commands:
                    print(f"    {command}")
                if result.returncode != 0:
                    failures += 1
                    print(result.stdout[-3000:], result.stderr[-3000:], sep="\n")
        for line in skipped:
            print(f"not run (marked): {line}")
        print(f"{ran} documented commands run, {failures} blocks failed, {len(skipped)} marked")
        return 1 if failures or ran == 0 else 0
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
