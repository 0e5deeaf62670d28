#!/usr/bin/env python3
"""ctest docs.api_reference: the API reference (cmake/api_reference.py, clang-doc) holds what
the public headers say.

    check_api_reference.py --clang-doc PROGRAM --source DIR [-I DIR ...]

Writes the reference into a scratch folder, then, reading the headers apart from clang-doc:
every class or struct of include/microrelief declared at a line's start under a // comment
has its page, and the page carries that comment's first words; no page names the machine's
own source path; every link of the index and the namespace pages names a page that exists.
Python 3, the standard library only.
"""

import argparse
import pathlib
import re
import subprocess
import sys
import tempfile

DECLARATION = re.compile(r"^(?:struct|class)\s+(\w+)\b[^;]*$")
LINK = re.compile(r"\]\(([^)#]+)\)")
WORDS = 8  # a comment's first words that its page must carry


def documented_records(source):
    """(header, name, first words) for each record declared under a comment."""
    records = []
    for header in sorted((source / "include" / "microrelief").rglob("*.h")):
        lines = header.read_text(encoding="utf-8").splitlines()
        for k, line in enumerate(lines):
            match = DECLARATION.match(line)
            if not match or k == 0 or not lines[k - 1].lstrip().startswith("//"):
                continue
            first = k
            while first > 0 and lines[first - 1].lstrip().startswith("//"):
                first -= 1
            words = " ".join(l.lstrip()[2:] for l in lines[first:k]).split()
            records.append((header.relative_to(source).as_posix(), match.group(1),
                            " ".join(words[:WORDS])))
    return records


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--clang-doc", required=True)
    parser.add_argument("--source", required=True, type=pathlib.Path)
    parser.add_argument("-I", dest="includes", action="append", default=[])
    args = parser.parse_args()
    source = args.source.resolve()
    failures = []
    with tempfile.TemporaryDirectory(prefix="microrelief-api-check-") as scratch:
        out = pathlib.Path(scratch) / "api"
        command = [sys.executable, str(source / "cmake" / "api_reference.py"),
                   "--clang-doc", args.clang_doc, "--source", str(source), "--out", str(out)]
        for include in args.includes:
            command += ["-I", include]
        run = subprocess.run(command, capture_output=True, text=True)
        if run.returncode != 0:
            print(f"docs.api_reference: the generator failed: {run.stderr.strip()}")
            return 1

        pages = {}
        for page in out.rglob("*.md"):
            pages.setdefault(page.stem, []).append(page)
        records = documented_records(source)
        for header, name, words in records:
            texts = [" ".join(p.read_text(encoding="utf-8").split()) for p in pages.get(name, [])]
            if not texts:
                failures.append(f"{header}: {name} has no page")
            elif not any(words in text for text in texts):
                failures.append(f"{header}: {name}'s page lacks its comment ('{words} ...')")

        for page in out.rglob("*.md"):
            text = page.read_text(encoding="utf-8")
            if str(source) in text:
                failures.append(f"{page.relative_to(out)} names the build machine's {source}")
            if page.name == "index.md":
                for target in LINK.findall(text):
                    if not (page.parent / target).exists():
                        failures.append(f"{page.relative_to(out)} links to {target}, not written")

    for failure in failures:
        print(f"docs.api_reference: {failure}")
    if failures:
        return 1
    print(f"docs.api_reference: {len(records)} documented records, each on its page "
          f"with its comment")
    return 0


if __name__ == "__main__":
    sys.exit(main())
