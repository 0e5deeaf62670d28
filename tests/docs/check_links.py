#!/usr/bin/env python3
"""Checks that every relative link and image path in README.md and docs/**/*.md resolves.

A link [text](target) or image ![alt](target) whose target is not a URL (http:, https:,
mailto:, ...) must name a file or folder that exists, relative to the Markdown file that
holds it; a target with #anchor (or a bare #anchor, the same file) must also name a
heading of that Markdown file, as GitHub makes anchors of headings. Links inside code
(fenced blocks, indented blocks, `spans`) are text, not links, and are not checked.

Usage: check_links.py [REPOSITORY_ROOT]   (default: two folders above this script)
Exit status 0 when every link resolves; 1, with one line per broken link, when not.
"""
import os
import re
import sys
import urllib.parse

LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\[\]]*\])*\]\(\s*<?([^()\s<>]*(?:\([^()\s]*\)[^()\s<>]*)*)>?(?:\s+\"[^\"]*\")?\s*\)")
REFERENCE = re.compile(r"^\s{0,3}\[[^\]]+\]:\s*<?(\S+?)>?(?:\s+.*)?$")
HEADING = re.compile(r"^\s{0,3}(#{1,6})\s+(.*?)\s*#*\s*$")
FENCE = re.compile(r"^\s{0,3}(`{3,}|~{3,})")
SCHEME = re.compile(r"^[A-Za-z][A-Za-z0-9+.-]*:")


def prose_lines(text):
    """The file's lines with code blanked out: fenced and indented blocks, code spans."""
    lines = []
    fence = None
    previous_blank = True
    in_indented = False
    for line in text.split("\n"):
        marker = FENCE.match(line)
        if fence:
            if marker and marker.group(1)[0] == fence[0] and len(marker.group(1)) >= len(fence):
                fence = None
            lines.append("")
            continue
        if marker:
            fence = marker.group(1)
            lines.append("")
            continue
        indented = line.startswith("    ") or line.startswith("\t")
        if indented and (previous_blank or in_indented) and line.strip():
            in_indented = True
            lines.append("")
            continue
        if line.strip():
            in_indented = False
        previous_blank = not line.strip()
        lines.append(re.sub(r"(`+)(.+?)\1", "", line))
    return lines


def slug(heading):
    """GitHub's anchor for a heading: lower case, punctuation dropped, spaces to hyphens."""
    text = re.sub(r"`([^`]*)`", r"\1", heading)
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", text)
    text = re.sub(r"<[^>]+>", "", text).strip().lower()
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


_anchors = {}


def anchors(path):
    cache = _anchors
    if path not in cache:
        with open(path, encoding="utf-8") as f:
            text = f.read()
        seen = {}
        found = set()
        for line in prose_lines_keep_headings(text):
            match = HEADING.match(line)
            if not match:
                continue
            base = slug(match.group(2))
            count = seen.get(base, 0)
            seen[base] = count + 1
            found.add(base if count == 0 else f"{base}-{count}")
        cache[path] = found
    return cache[path]


def prose_lines_keep_headings(text):
    """Lines outside fenced code (headings may hold code spans, which name anchors)."""
    fence = None
    for line in text.split("\n"):
        marker = FENCE.match(line)
        if fence:
            if marker and marker.group(1)[0] == fence[0] and len(marker.group(1)) >= len(fence):
                fence = None
            continue
        if marker:
            fence = marker.group(1)
            continue
        yield line


def check_file(path, root):
    """(links checked, problems) of one Markdown file."""
    problems = []
    checked = 0
    with open(path, encoding="utf-8") as f:
        text = f.read()
    lines = prose_lines(text)
    prose = "\n".join(lines)
    found = []  # (line number, target): a link's text may run over several lines
    for match in LINK.finditer(prose):
        found.append((prose.count("\n", 0, match.start()) + 1, match.group(1)))
    for number, line in enumerate(lines, 1):
        reference = REFERENCE.match(line)
        if reference:
            found.append((number, reference.group(1)))
    for number, target in sorted(found):
        checked += 1
        problem = check_target(path, target)
        if problem:
            problems.append(f"{os.path.relpath(path, root)}:{number}: {target}: {problem}")
    return checked, problems


def check_target(path, target):
    if not target:
        return "empty link"
    if SCHEME.match(target) or target.startswith("//"):
        return None  # a URL: not ours to resolve
    file_part, _, anchor = target.partition("#")
    file_part = urllib.parse.unquote(file_part.split("?")[0])
    if file_part:
        if file_part.startswith("/"):
            return "absolute path (links must be relative)"
        resolved = os.path.normpath(os.path.join(os.path.dirname(path), file_part))
        if not os.path.exists(resolved):
            return "no such file"
    else:
        resolved = path
    if anchor:
        if not resolved.endswith(".md") or not os.path.isfile(resolved):
            return "an anchor into something that is not a Markdown file"
        if urllib.parse.unquote(anchor).lower() not in anchors(resolved):
            return f"no heading for #{anchor} in {os.path.basename(resolved)}"
    return None


def markdown_files(root):
    files = [os.path.join(root, "README.md")]
    for folder, subfolders, names in os.walk(os.path.join(root, "docs")):
        subfolders.sort()
        files += [os.path.join(folder, n) for n in sorted(names) if n.endswith(".md")]
    return [f for f in files if os.path.isfile(f)]


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", ".."))
    files = markdown_files(root)
    if not files:
        print(f"check_links: no README.md or docs/ under {root}", file=sys.stderr)
        return 1
    checked = 0
    problems = []
    for path in files:
        count, found = check_file(path, root)
        checked += count
        problems += found
    for problem in problems:
        print(problem)
    if problems:
        print(f"check_links: {len(problems)} of {checked} links in {len(files)} Markdown files do not resolve",
              file=sys.stderr)
        return 1
    print(f"check_links: all {checked} links in {len(files)} Markdown files resolve (URLs not followed)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
