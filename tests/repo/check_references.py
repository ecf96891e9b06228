#!/usr/bin/python3
"""Every reference in the repository resolves inside it (CTest entry repo.references, label unit).

A clone is all a user has, so:
  1. no file may refer to a place outside the repository: the design notes that once lived beside it
     (the upper-case notes, or the folder "shared" beside it), or an absolute path of the machine it was
     written on;
  2. every repository path that README.md, FORMAT.md and the Markdown pages under docs/ and bench/ mention
     (docs/..., tools/..., inputs/..., src/..., bench/..., tests/...), and every relative Markdown link in
     them, must exist (a '*' in a path is a glob that must match something; a path without an extension may
     be the stem of existing files, as an output prefix such as docs/repose/pile_none is).
  3. every "docs/<page>.md section N" (or "sections N and M") names a section that the page has (a heading
     "## N. ...").
Each failure is printed as FILE:LINE: what; the exit status is 1 when there is one, 2 when the check
itself cannot run, 0 otherwise.
  /usr/bin/python3 tests/repo/check_references.py [REPO_ROOT]
"""
import glob
import os
import re
import subprocess
import sys

# Built from parts so that this file does not match itself.
NOTES = ["DESIGN", "PHYSICS", "VALIDATION"]
OUTSIDE = [
    (re.compile(r"\b(" + "|".join(NOTES) + r")\.md\b"),
     "names a design note outside the repository (use docs/design.md, docs/physics.md, docs/validation.md)"),
    (re.compile(r"\.\./" + "shared" + r"\b"), "refers to a folder beside the repository"),
    (re.compile(r"(?<![\w.~-])/" + "work" + r"/"), "refers to an absolute path outside the repository"),
]

# Repository paths in prose: a top-level folder of the repository, then a path.
PATH = re.compile(r"(?<![\w/.<>-])((?:docs|tools|inputs|src|bench|tests)/[A-Za-z0-9_.*/-]*)")
# Relative Markdown links and images: [text](target) with a target that is not a URL or an anchor.
LINK = re.compile(r"\]\(([^)\s#]+)(?:#[^)]*)?\)")
# "docs/physics.md section 4", "docs/design.md sections 8 and 10", "docs/validation.md sections 0, 2 and 6".
SECTION = re.compile(r"(docs/[\w-]+\.md)(?:'s)? sections? (\d+(?:(?:, | and |, and )\d+)*)")
HEADING = re.compile(r"^## (\d+)\.", re.M)
# Paths the prose names on purpose although they do not exist: the example of how to add a law.
EXAMPLES = {"src/physics/RollingMyLaw.hpp", "tests/physics/test_rolling_mylaw.cpp"}


def repository_files(root):
    """Tracked and untracked-but-not-ignored files (git), or a walk that skips build*/ and .git."""
    try:
        out = subprocess.run(["git", "-C", root, "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
                             check=True, capture_output=True).stdout
        return sorted({f for f in out.decode().split("\0") if f and os.path.isfile(os.path.join(root, f))})
    except (OSError, subprocess.CalledProcessError):
        files = []
        for d, subdirs, names in os.walk(root):
            subdirs[:] = [s for s in subdirs if s != ".git" and not (d == root and s.startswith("build"))]
            files += [os.path.relpath(os.path.join(d, n), root) for n in names]
        return sorted(files)


def text_of(path):
    """The file's text, or None for a binary file."""
    with open(path, "rb") as f:
        data = f.read()
    if b"\0" in data:
        return None
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        return None


def exists(root, rel):
    rel = rel.rstrip(".,:;")
    if rel in EXAMPLES or not rel:
        return True
    full = os.path.join(root, rel)
    if "*" in rel:
        return bool(glob.glob(full))
    stem = not os.path.splitext(rel)[1] and not rel.endswith("/")
    return os.path.exists(full) or (stem and bool(glob.glob(full + ".*") + glob.glob(full + "_*")))


def documented_pages(files):
    return [f for f in files if f in ("README.md", "FORMAT.md") or
            (f.endswith(".md") and (f.startswith("docs/") or f.startswith("bench/")))]


def main(argv):
    root = os.path.abspath(argv[1] if len(argv) > 1 else os.path.join(os.path.dirname(__file__), "..", ".."))
    if not os.path.isfile(os.path.join(root, "CMakeLists.txt")):
        print(f"check_references: ERROR: {root} is not the repository root (no CMakeLists.txt)", file=sys.stderr)
        return 2
    files = repository_files(root)
    failures = []
    texts = {}
    for f in files:
        text = text_of(os.path.join(root, f))
        if text is None:
            continue
        texts[f] = text
        for n, line in enumerate(text.splitlines(), 1):
            for pattern, what in OUTSIDE:
                m = pattern.search(line)
                if m:
                    failures.append(f"{f}:{n}: '{m.group(0)}' {what}")
    sections = {}
    for f, text in texts.items():
        for n, line in enumerate(text.splitlines(), 1):
            for m in SECTION.finditer(line):
                page = m.group(1)
                if page not in sections:
                    sections[page] = set(HEADING.findall(texts.get(page, "")))
                for number in re.findall(r"\d+", m.group(2)):
                    if number not in sections[page]:
                        failures.append(f"{f}:{n}: {page} has no section {number}")
    for f in documented_pages(files):
        here = os.path.dirname(f)
        for n, line in enumerate(texts.get(f, "").splitlines(), 1):
            for m in PATH.finditer(line):
                if not exists(root, m.group(1)):
                    failures.append(f"{f}:{n}: '{m.group(1).rstrip('.,:;')}' does not exist in the repository")
            for m in LINK.finditer(line):
                target = m.group(1)
                if re.match(r"^[a-z]+:", target):
                    continue  # a URL
                if not exists(root, os.path.normpath(os.path.join(here, target))):
                    failures.append(f"{f}:{n}: link '{target}' does not resolve inside the repository")
    for message in failures:
        print(message)
    if failures:
        print(f"check_references: {len(failures)} reference(s) outside the repository or to missing files",
              file=sys.stderr)
        return 1
    print(f"check_references: {len(texts)} text files, {len(documented_pages(files))} pages: every reference "
          "resolves inside the repository")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
