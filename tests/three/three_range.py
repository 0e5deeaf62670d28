#!/usr/bin/env python3
"""microrelief-three on the ends of its peer range (ctest three.range, label three).

package.json's peer range has a lower bound only (`three >=0.171.0`: the oldest three the
tests pass on). This runs the package's browser tests (microrelief-three-tests, the suites
on ThreePage.h's fixture) once for each end of that range that is not the package's own
three (its devDependency, which ctest three runs): the oldest, from the peer range, and
the newest the npm registry has (`npm view three version`, asked at each run, so that a new
release is tried on its first day). For each, the staged site (the build tree's
share/microrelief) is copied with that three installed in web/three/node_modules/three
and the tests are pointed at it through MICRORELIEF_THREE_SITE.

usage: three_range.py --tests EXE --stage DIR --package DIR --npm NPM --node NODE
                      [--work DIR] [--filter GTEST_FILTER]
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys


def fail(message):
    print(f"three_range: {message}", file=sys.stderr)
    sys.exit(1)


def run(command, **kwargs):
    return subprocess.run(command, capture_output=True, text=True, **kwargs)


def oldest_in_range(package):
    with open(os.path.join(package, "package.json"), encoding="utf-8") as f:
        meta = json.load(f)
    peer = meta.get("peerDependencies", {}).get("three", "")
    found = re.fullmatch(r">=(\d+\.\d+\.\d+)", peer.strip())
    if not found:
        fail(f"{package}/package.json: peerDependencies.three is '{peer}', expected a lower bound only (>=0.x.y)")
    return found.group(1), meta["devDependencies"]["three"]


def newest_on_registry(npm):
    r = run([npm, "view", "three", "version"])
    version = r.stdout.strip()
    if r.returncode != 0 or not re.fullmatch(r"\d+\.\d+\.\d+", version):
        fail("cannot ask the npm registry for three's newest version (`npm view three version`: "
             + (r.stderr.strip().splitlines() or ["no answer"])[-1] + "); this test needs the registry")
    return version


def installed_three(work, npm, version):
    """three@version installed under work/npm-<version> (kept between runs)."""
    prefix = os.path.join(work, f"npm-{version}")
    three = os.path.join(prefix, "node_modules", "three")
    meta = os.path.join(three, "package.json")
    if os.path.exists(meta):
        with open(meta, encoding="utf-8") as f:
            if json.load(f).get("version") == version:
                return three
    os.makedirs(prefix, exist_ok=True)
    r = run([npm, "install", "--prefix", prefix, "--no-save", "--no-audit", "--no-fund",
             "--prefer-offline", f"three@{version}"])
    if r.returncode != 0 or not os.path.exists(meta):
        fail(f"npm install three@{version} failed: " + (r.stderr.strip().splitlines() or ["no message"])[-1])
    return three


def site_with(work, stage, three, version):
    """A copy of the staged site whose example imports three@version."""
    site = os.path.join(work, f"site-{version}")
    shutil.rmtree(site, ignore_errors=True)
    shutil.copytree(stage, site, ignore=lambda folder, names: ["three"] if folder.endswith(
        os.path.join("web", "three", "node_modules")) else [])
    shutil.copytree(three, os.path.join(site, "web", "three", "node_modules", "three"))
    return site


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--tests", required=True, help="microrelief-three-tests")
    parser.add_argument("--stage", required=True, help="the build tree's share/microrelief")
    parser.add_argument("--package", required=True, help="packages/microrelief-three")
    parser.add_argument("--npm", required=True)
    parser.add_argument("--node", required=True)
    parser.add_argument("--work", default="three-range", help="scratch folder (installs kept)")
    # The browser suites but the WebGPU example's (ThreePage.RendererWebGPU*): the WebGPU entry
    # is held on the package's own three (ctest three.webgpu, three.webgpu_example), and its
    # ReliefStandardNodeMaterial, which the example's lit scene draws with, needs three r187
    # (overrideNodes) and refuses an older one in one line (docs/three.md).
    parser.add_argument("--filter", default="-ThreeTarball.*:ThreePackage.*:ThreePage.RendererWebGPU*",
                        help="the suites to run on each end (default: the browser suites but the WebGPU example's)")
    args = parser.parse_args()
    if not os.path.exists(os.path.join(args.stage, "web", "three", "index.html")):
        fail(f"{args.stage}/web/three is not staged: build the microrelief-three target")
    os.environ["PATH"] = os.pathsep.join([os.path.dirname(args.node), os.path.dirname(args.npm),
                                          os.environ.get("PATH", "")])

    oldest, own = oldest_in_range(args.package)
    newest = newest_on_registry(args.npm)
    print(f"three_range: the peer range's oldest three is {oldest}, the registry's newest {newest}, "
          f"the package's own {own} (ctest three)", flush=True)
    failed = []
    for label, version in (("oldest", oldest), ("newest", newest)):
        if version == own:
            print(f"three_range: the {label}, {version}, is the package's own three: ctest three runs it", flush=True)
            continue
        site = site_with(os.path.abspath(args.work), args.stage,
                         installed_three(os.path.abspath(args.work), args.npm, version), version)
        print(f"three_range: the {label}, three {version}: {args.filter} on {site}", flush=True)
        r = subprocess.run([args.tests, f"--gtest_filter={args.filter}"],
                           env={**os.environ, "MICRORELIEF_THREE_SITE": site})
        print(f"three_range: three {version}: {'passed' if r.returncode == 0 else 'FAILED'}", flush=True)
        if r.returncode != 0:
            failed.append(version)
    if failed:
        fail("the package's tests failed on three " + ", ".join(failed))


if __name__ == "__main__":
    main()
