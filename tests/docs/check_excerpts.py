#!/usr/bin/env python3
"""Checks that code a page quotes from the repository is the file as it stands.

In README.md, docs/**/*.md and the packages' READMEs (packages/*/README.md), a fenced code
block right after a line `<!-- excerpt: PATH from LINE -->` (PATH from the
repository root, LINE counted from 1) must hold exactly the lines of PATH from LINE to its
end: the page shows the file, and this keeps the two one source (a change to the file
without the page, or to the page without the file, fails here). A marker ending
`, at most N lines -->` also holds the file to that length from LINE on (a page that
promises "the user's code in at most 30 lines" keeps its word).

Usage: check_excerpts.py [REPOSITORY_ROOT]   (default: two folders above this script)
Exit status 0 when every excerpt matches (and at least one was found); 1, saying which
does not, when not.
"""
import pathlib
import re
import sys

MARKER = re.compile(r"^<!-- excerpt: (\S+) from (\d+)(?:, at most (\d+) lines)? -->$")
FENCE = re.compile(r"^(`{3,}|~{3,})")


def excerpts(text):
    """(path, first line, the block's lines, the marker's line number, the most lines or
    None) of each excerpt."""
    lines = text.split("\n")
    for k, line in enumerate(lines):
        marker = MARKER.match(line)
        if not marker:
            continue
        fence = FENCE.match(lines[k + 1]) if k + 1 < len(lines) else None
        most = int(marker.group(3)) if marker.group(3) else None
        if not fence:
            yield marker.group(1), int(marker.group(2)), None, k + 1, most
            continue
        end = k + 2
        while end < len(lines) and not lines[end].startswith(fence.group(1)):
            end += 1
        yield marker.group(1), int(marker.group(2)), lines[k + 2:end], k + 1, most


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parents[2])
    pages = [root / "README.md", *sorted((root / "docs").rglob("*.md")), *sorted(root.glob("packages/*/README.md"))]
    found, bad = 0, []
    for page in pages:
        for path, first, block, at, most in excerpts(page.read_text(encoding="utf-8")):
            found += 1
            where = f"{page.relative_to(root)}:{at}"
            if block is None:
                bad.append(f"{where}: the excerpt marker is not followed by a fenced code block")
                continue
            source = root / path
            if not source.is_file():
                bad.append(f"{where}: {path}: no such file")
                continue
            want = source.read_text(encoding="utf-8").rstrip("\n").split("\n")[first - 1:]
            if most is not None and len(want) > most:
                bad.append(f"{where}: {path} has {len(want)} lines from line {first}, more than the "
                           f"{most} the page promises")
                continue
            if block != want:
                differs = next((n for n, (a, b) in enumerate(zip(block, want)) if a != b), min(len(block), len(want)))
                bad.append(f"{where}: differs from {path} at its line {first + differs} "
                           f"(the page has {len(block)} lines, the file {len(want)} from line {first})")
    for line in bad:
        print(line)
    if not found:
        print("check_excerpts: no excerpt found (the marker's spelling changed?)")
        return 1
    print(f"check_excerpts: {found - len(bad)} of {found} excerpts match their files")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
