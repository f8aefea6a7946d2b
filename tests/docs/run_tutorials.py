#!/usr/bin/env python3
"""Run every command shown in the tutorials (docs/tutorials/*.md), in order, so they cannot go stale.

    /usr/bin/python3 tests/docs/run_tutorials.py SWELL [TUTORIAL.md ...] [--keep DIR]

SWELL is the swell binary to test (ctest passes $<TARGET_FILE:swell>). Without TUTORIAL.md
arguments every docs/tutorials/*.md except index.md is run. Standard library only.

What is run. In a tutorial, a fenced block of kind `console` holds commands and their output:

    ```console
    $ swell run cases/dambreak2d.yaml        <- a command ("$ " prompt)
    case dambreak2d (cases/dambreak2d.yaml) ... <- output: shown to the reader, not checked
    ```

Every line that starts with "$ " is a command; a command whose line ends in a backslash
continues on the next line(s). Other blocks (```sh, ```yaml, ```text) are never run: use them for
what a reader types elsewhere (ParaView) or for file contents. A command is expected to exit 0,
or with N when its line ends in the comment `# exit code N`.

Hints for the test, invisible in the HTML (MyST comments, lines starting with "%"); each applies
to the next `console` block of the file:

    % test: append ARGS         ARGS appended to each `swell run` / `swell foam` command of the
                                block (shortens long runs: `--set time.end=0.02`); the reader's
                                command stays the real one
    % test: replace OLD => NEW  literal replacement in the block's commands (e.g. `--end 0.3`)
    % test: before COMMAND      a shell command run before the block (e.g. copy committed results
                                where the shortened run cannot give the analysis its window)
    % test: requires PROGRAM    PROGRAM must be on PATH for this block and every later one; where
                                it is not, they are skipped and the script exits 77 (ctest's
                                SKIP_RETURN_CODE) once the earlier blocks have passed

How. Each tutorial runs as one bash process (so `export` and `cd` carry from one command to the
next, as in the reader's shell) in a fresh temporary folder laid out like the root of a checkout:
build/swell (a link to SWELL), copies of cases/ and docs/tutorials/, and validation/ (a link; the
tutorials only read it). Outputs go there (out/...), never into the source tree. The folder is
removed at the end unless --keep DIR is given (then it is DIR, which must not exist).

Exit: 0 all passed, 1 a command failed (the log says which, with its line in the tutorial),
2 bad usage or a malformed tutorial, 77 skipped (a `requires` program is missing).
"""
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
import time

SRC = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
TUTORIALS = os.path.join(SRC, "docs", "tutorials")
FENCE = re.compile(r"^(\s*)(`{3,}|~{3,})\s*(\S*)")
EXPECT = re.compile(r"#\s*exit code (\d+)\s*$")
HINT = re.compile(r"^%\s*test:\s*(append|replace|before|requires)\s+(.*?)\s*$")
SHORTENED = re.compile(r"^swell\s+(run|foam)\b")
SKIP = 77


class Malformed(Exception):
    pass


def parse(path):
    """[(line, command, expected exit, [before commands], requires)] of the file's console blocks."""
    lines = open(path, encoding="utf-8").read().split("\n")
    out, hints, requires = [], [], None
    i = 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        h = HINT.match(lines[i])
        if h:
            hints.append((h.group(1), h.group(2), i + 1))
            i += 1
            continue
        if not m:
            i += 1
            continue
        fence, kind = m.group(2), m.group(3)
        body_start = i + 1
        j = body_start
        while j < len(lines) and not lines[j].strip().startswith(fence):
            j += 1
        if j == len(lines):
            raise Malformed(f"{path}:{i + 1}: unclosed code block")
        if kind != "console":
            if hints:
                raise Malformed(f"{path}:{hints[0][2]}: a test hint before a `{kind}` block "
                                "(hints apply to the next `console` block)")
            i = j + 1
            continue
        append, replace, before = [], [], []
        for key, value, lno in hints:
            if key == "append":
                append.append(value)
            elif key == "replace":
                if "=>" not in value:
                    raise Malformed(f"{path}:{lno}: expected `% test: replace OLD => NEW`")
                old, new = (v.strip() for v in value.split("=>", 1))
                replace.append((old, new, lno))
            elif key == "before":
                before.append(value)
            else:
                requires = value
        hints = []
        block = lines[body_start:j]
        commands = []
        k = 0
        while k < len(block):
            line = block[k]
            if not line.startswith("$ "):
                k += 1
                continue
            lno = body_start + k + 1
            text = line[2:]
            while text.endswith("\\") and k + 1 < len(block):
                k += 1
                text = text + "\n" + block[k]
            k += 1
            e = EXPECT.search(text)
            expected = int(e.group(1)) if e else 0
            commands.append([lno, text, expected])
        if not commands:
            raise Malformed(f"{path}:{i + 1}: a `console` block without a `$ ` command")
        for old, new, lno in replace:
            hits = [c for c in commands if old in c[1]]
            if not hits:
                raise Malformed(f"{path}:{lno}: `{old}` is in no command of the next block")
            for c in hits:
                c[1] = c[1].replace(old, new)
        if append:
            hits = [c for c in commands if SHORTENED.match(c[1])]
            if not hits:
                raise Malformed(f"{path}:{i + 1}: `% test: append` before a block without "
                                "`swell run` or `swell foam`")
            for c in hits:
                c[1] = strip_comment(c[1]) + " " + " ".join(append)
        for n, (lno, text, expected) in enumerate(commands):
            out.append((lno, text, expected, before if n == 0 else [], requires))
        i = j + 1
    if hints:
        raise Malformed(f"{path}:{hints[0][2]}: a test hint with no `console` block after it")
    return out


def strip_comment(text):
    """The command without a trailing `# ...` comment (so appended options are not commented):
    the first `#` outside quotes that starts a word."""
    quote = None
    for pos, ch in enumerate(text):
        if quote:
            if ch == quote:
                quote = None
        elif ch in "'\"":
            quote = ch
        elif ch == "#" and (pos == 0 or text[pos - 1].isspace()):
            return text[:pos].rstrip()
    return text


def setup_tree(root, swell):
    os.makedirs(os.path.join(root, "build"))
    os.symlink(os.path.abspath(swell), os.path.join(root, "build", "swell"))
    shutil.copytree(os.path.join(SRC, "cases"), os.path.join(root, "cases"))
    shutil.copytree(TUTORIALS, os.path.join(root, "docs", "tutorials"))
    os.symlink(os.path.join(SRC, "validation"), os.path.join(root, "validation"))


def script_for(path, commands):
    name = os.path.relpath(path, SRC)
    s = ["# generated by tests/docs/run_tutorials.py from " + name,
         "__now() { date +%s%N; }"]
    for n, (lno, text, expected, before, _) in enumerate(commands):
        for b in before:
            s.append("echo " + shlex.quote(f"--- (test only, before line {lno}) $ {b}"))
            s.append(b)
            s.append("__rc=$?; if [ $__rc -ne 0 ]; then echo " +
                     shlex.quote(f"FAILED: test setup before {name}:{lno}: {b}") +
                     " \"exited $__rc\"; exit 101; fi")
        s.append("echo " + shlex.quote(f"--- [{n + 1}/{len(commands)}] {name}:{lno} $ {text}"))
        s.append("__t0=$(__now)")
        s.append(text)
        s.append("__rc=$?")
        s.append("__ms=$(( ($(__now) - __t0) / 1000000 ))")
        s.append("echo \"--- exit $__rc, $((__ms / 1000)).$(printf %03d $((__ms % 1000))) s\"")
        s.append(f"if [ $__rc -ne {expected} ]; then echo " +
                 shlex.quote(f"FAILED: {name}:{lno}: expected exit code {expected}, got") +
                 " $__rc; exit 101; fi")
    s.append("exit 0")
    return "\n".join(s) + "\n"


def run_tutorial(path, swell, keep):
    commands = parse(path)
    if not commands:
        raise Malformed(f"{path}: no `console` block: nothing to test")
    skipped = [c for c in commands if c[4] and shutil.which(c[4]) is None]
    runnable = [c for c in commands if not (c[4] and shutil.which(c[4]) is None)]
    root = keep or tempfile.mkdtemp(prefix="swell_tutorial_")
    if keep:
        os.makedirs(root)
    try:
        setup_tree(root, swell)
        script = os.path.join(root, "tutorial.sh")
        with open(script, "w") as f:
            f.write(script_for(path, runnable))
        t0 = time.time()
        rc = subprocess.call(["bash", "--noprofile", "--norc", script], cwd=root)
        wall = time.time() - t0
    finally:
        if not keep:
            shutil.rmtree(root, ignore_errors=True)
    name = os.path.relpath(path, SRC)
    if rc != 0:
        print(f"=== {name}: FAILED after {wall:.1f} s (the command above)", flush=True)
        return 1
    print(f"=== {name}: {len(runnable)} commands passed in {wall:.1f} s", flush=True)
    if skipped:
        print(f"=== {name}: SKIPPED {len(skipped)} commands from line {skipped[0][0]} on: "
              f"`{skipped[0][4]}` is not on PATH", flush=True)
        return SKIP
    return 0


def main(argv):
    args, keep = [], None
    it = iter(argv)
    for a in it:
        if a == "--keep":
            keep = next(it, None)
            if not keep:
                print("--keep needs a folder", file=sys.stderr)
                return 2
            keep = os.path.abspath(keep)
        else:
            args.append(a)
    if not args:
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        return 2
    swell, files = args[0], args[1:]
    if not (os.path.isfile(swell) and os.access(swell, os.X_OK)):
        print(f"{swell}: not an executable file", file=sys.stderr)
        return 2
    if not files:
        files = sorted(os.path.join(TUTORIALS, f) for f in os.listdir(TUTORIALS)
                       if f.endswith(".md") and f != "index.md")
    if keep and len(files) > 1:
        print("--keep takes one tutorial", file=sys.stderr)
        return 2
    # Every tutorial must be in the tutorials' toctree (docs/tutorials/index.md).
    index = open(os.path.join(TUTORIALS, "index.md"), encoding="utf-8").read()
    worst = 0
    for f in files:
        stem = os.path.splitext(os.path.basename(f))[0]
        if not re.search(r"^" + re.escape(stem) + r"\s*$", index, re.M):
            print(f"{f}: not in the toctree of docs/tutorials/index.md", file=sys.stderr)
            return 2
        try:
            rc = run_tutorial(os.path.abspath(f), swell, keep)
        except Malformed as e:
            print(f"malformed tutorial: {e}", file=sys.stderr)
            return 2
        if rc == 1:
            worst = 1
        elif rc == SKIP and worst == 0:
            worst = SKIP
    return worst


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
