#!/usr/bin/env python3
"""Pack built programs to run on a machine without Debian 12's packages (a borrowed GPU).

    python3 scripts/gpu-bundle.py OUT PROGRAM...

OUT gets bin/ (the programs), share/microrelief (their shaders and assets, as the build
lays them out), lib/ (the shared libraries they load), lib/fallback/ (the C++ runtime,
for a machine whose own is older) and maps/ (the real maps scripts/bench-maps.sh fetched,
from $MICRORELIEF_BENCH_MAPS or out/bench-maps, where there are any). Run a program as

    LD_LIBRARY_PATH=OUT/lib OUT/bin/PROGRAM

Why stubs: Debian's OpenImageIO links every codec it has a plugin for (ffmpeg, OpenCV,
OpenVDB, DCMTK, libheif, LibRaw...) and GDAL every format it reads; with them the programs
load 360 MB of libraries, more than a borrowed machine's upload takes. The programs need a
few of them (PNG, BMP, TIFF and OpenEXR through OpenImageIO); KEEP names those, copied as
they are. Every other library is replaced by a stub of the same soname that defines each
symbol the programs and the kept libraries take from the real one, with its version, so the
dynamic linker (OpenImageIO is linked with BIND_NOW) is satisfied; a stub's function
returns a pointer to zeros, an empty string (OpenImageIO's static constructors call some of
DCMTK's, its plugin catalogue asks each codec for its version), its data are zeros.
A run that reads a format whose library is a stub fails there: it is for the benchmark and
the GL tests, which read PNG, BMP, TIFF and OpenEXR. The stubs hold no code
of the libraries they stand for. glibc and the GL loaders (libEGL, libGLdispatch: the GPU's
driver plugs into them) come from the machine; libEGL and libGLdispatch are copied too, for
a machine that lacks them.
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

# What the programs use, and what those need to load (no stub of these).
KEEP = [
    r"libOpenImageIO(_Util)?\.so", r"libz\.so", r"libpng16\.so", r"libjpeg\.so",
    r"libtiff\.so", r"libzstd\.so", r"liblzma\.so", r"libLerc\.so", r"libjbig\.so",
    r"libdeflate\.so", r"libwebp\.so", r"libsharpyuv\.so", r"libOpenEXR(Core)?-", r"libIex-",
    r"libIlmThread-", r"libImath-", r"libOpenColorIO\.so", r"libyaml-cpp\.so",
    r"libexpat\.so", r"libpystring\.so", r"liblcms2\.so", r"libtbb\.so", r"libboost_",
    r"libfreetype\.so", r"libbrotli(dec|common)\.so", r"libbz2\.so", r"libEGL\.so",
    r"libGLdispatch\.so",
]
# From the machine: glibc's parts.
SYSTEM = [r"^libc\.so", r"^libm\.so", r"^libpthread\.so", r"^libdl\.so", r"^librt\.so",
          r"^ld-linux", r"^linux-vdso"]
RUNTIME = [r"^libstdc\+\+\.so", r"^libgcc_s\.so"]


def closure(programs):
    """soname -> path of every library the programs load, as this machine resolves them."""
    libs = {}
    for program in programs:
        out = subprocess.run(["ldd", program], check=True, capture_output=True, text=True).stdout
        for line in out.splitlines():
            m = re.match(r"\s*(\S+) => (\S+)", line)
            if m and m.group(2).startswith("/"):
                libs[m.group(1)] = m.group(2)
    return libs


def matches(patterns, name):
    return any(re.search(p, name) for p in patterns)


def dynamic_symbols(path):
    """readelf's fields for each entry of the library's dynamic symbol table."""
    out = subprocess.run(["readelf", "-W", "--dyn-syms", path], check=True,
                         capture_output=True, text=True).stdout
    for line in out.splitlines():
        fields = line.split()
        if len(fields) >= 8 and fields[0].endswith(":"):
            yield fields


def exported_symbols(path):
    """(name, version or None, kind, size) for each symbol the library defines."""
    symbols = []
    for fields in dynamic_symbols(path):
        if fields[6] in ("UND", "ABS"):
            continue
        kind, bind, name = fields[3], fields[4], fields[7]
        if bind not in ("GLOBAL", "WEAK", "UNIQUE") or kind not in ("FUNC", "OBJECT", "TLS",
                                                                     "IFUNC", "NOTYPE"):
            continue
        version = None
        if "@@" in name:
            name, version = name.split("@@", 1)
        elif "@" in name:
            continue  # an old version, hidden; nothing links against it anew
        size = int(fields[2], 0) if fields[2].isdigit() or fields[2].startswith("0x") else 0
        symbols.append((name, version, kind, size))
    return symbols


def version_nodes(path):
    """The version names the library defines (its own soname's node excluded)."""
    out = subprocess.run(["readelf", "-W", "-V", path], check=True, capture_output=True,
                         text=True).stdout
    nodes, in_defs = [], False
    for line in out.splitlines():
        if "Version definition section" in line:
            in_defs = True
        elif "Version needs section" in line or "Version symbols section" in line:
            in_defs = False
        elif in_defs:
            m = re.search(r"Flags: (\S+).*Name: (\S+)", line)
            if m and m.group(1) != "BASE":
                nodes.append(m.group(2))
    return nodes


def undefined_symbols(path):
    """The names of the symbols a program or library takes from others."""
    return {fields[7].split("@")[0] for fields in dynamic_symbols(path) if fields[6] == "UND"}


def make_stub(soname, real, wanted, out_dir, work):
    """A library named soname that defines what wanted asks of real."""
    symbols = [s for s in exported_symbols(real) if s[0] in wanted]
    nodes = version_nodes(real)
    # Every function returns a pointer to zeros (an empty string): OpenImageIO's static
    # constructors call a few (DCMTK's globals), and its plugin catalogue asks each codec
    # library for its version string; nothing on the programs' paths calls one otherwise.
    asm = [".bss", ".balign 64", "__zeros: .zero 4096", ".text"]
    names = set()
    for name, version, kind, size in symbols:
        if name in names:
            continue
        names.add(name)
        label = '"%s"' % name
        if kind in ("FUNC", "IFUNC", "NOTYPE"):
            asm += [".text", ".globl %s" % label, ".type %s, @function" % label, "%s:" % label,
                    "  lea __zeros(%rip), %rax", "  ret"]
        elif kind == "TLS":
            asm += [".section .tbss,\"awT\",@nobits", ".globl %s" % label,
                    ".type %s, @tls_object" % label, ".size %s, %d" % (label, max(size, 1)),
                    "%s: .zero %d" % (label, max(size, 1))]
        else:
            asm += [".bss", ".balign 16", ".globl %s" % label, ".type %s, @object" % label,
                    ".size %s, %d" % (label, max(size, 1)), "%s: .zero %d" % (label, max(size, 1))]
    # The version script: each symbol in its node; a versioned library's unversioned
    # symbols (its base version) go in the first node, which a reference without a
    # version accepts.
    by_node = {node: [] for node in nodes}
    for name, version, _, _ in symbols:
        node = version or (nodes[0] if nodes else None)
        by_node.setdefault(node, []).append(name)
    if None in by_node:
        script = ["{ global: %s local: *; };" % "".join('"%s";' % n for n in sorted(set(by_node[None])))]
    else:
        script = ["%s { global: %s };" % (node, "".join('"%s";' % n for n in sorted(set(members))))
                  if members else "%s { };" % node for node, members in by_node.items()]
        script = script or ["{ };"]
        script[-1] = script[-1][:-2] + " local: *; };"
    base = os.path.join(work, soname)
    with open(base + ".S", "w") as f:
        f.write("\n".join(asm) + "\n.section .note.GNU-stack,\"\",@progbits\n")
    with open(base + ".map", "w") as f:
        f.write("\n".join(script) + "\n")
    subprocess.run(["gcc", "-shared", "-nostdlib", "-o", os.path.join(out_dir, soname),
                    "-Wl,-soname," + soname, "-Wl,--version-script=" + base + ".map",
                    base + ".S"], check=True)


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    out, programs = sys.argv[1], sys.argv[2:]
    root = os.path.dirname(os.path.dirname(os.path.abspath(programs[0])))
    lib, fallback = os.path.join(out, "lib"), os.path.join(out, "lib", "fallback")
    bin_dir = os.path.join(out, "bin")
    for d in (lib, fallback, bin_dir):
        os.makedirs(d, exist_ok=True)
    for program in programs:
        shutil.copy2(program, bin_dir)
    share = os.path.join(out, "share", "microrelief")
    shutil.rmtree(share, ignore_errors=True)
    shutil.copytree(os.path.join(root, "share", "microrelief"), share, symlinks=False)
    maps = os.environ.get("MICRORELIEF_BENCH_MAPS") or os.path.join("out", "bench-maps")
    if os.path.isfile(os.path.join(maps, "maps.txt")):
        shutil.rmtree(os.path.join(out, "maps"), ignore_errors=True)
        shutil.copytree(maps, os.path.join(out, "maps"),
                        ignore=shutil.ignore_patterns(".fetch.*"))
    else:
        print("gpu-bundle: no fetched maps in %s (scripts/bench-maps.sh fetches them): the "
              "benchmark there runs without them" % maps)
    stubbed, kept = [], []
    libraries = closure(programs)
    wanted = set()
    for program in programs:
        wanted |= undefined_symbols(program)
    with tempfile.TemporaryDirectory() as work:
        for soname, path in sorted(libraries.items()):
            if matches(SYSTEM, soname):
                continue
            if matches(RUNTIME, soname):
                shutil.copy2(path, os.path.join(fallback, soname))
            elif matches(KEEP, soname):
                shutil.copy2(path, os.path.join(lib, soname))
                kept.append(soname)
                wanted |= undefined_symbols(path)
        for soname, path in sorted(libraries.items()):
            if not (matches(SYSTEM, soname) or matches(RUNTIME, soname) or matches(KEEP, soname)):
                make_stub(soname, path, wanted, lib, work)
                stubbed.append(soname)
    # Only what the programs load through the stubs stays (a stub loads nothing).
    loaded = set()
    env = dict(os.environ, LD_LIBRARY_PATH=os.path.abspath(lib))
    for program in os.listdir(bin_dir):
        listing = subprocess.run(["ldd", os.path.join(bin_dir, program)], check=True, env=env,
                             capture_output=True, text=True).stdout
        if "not found" in listing:
            sys.exit("gpu-bundle: %s: a library was not found:\n%s" % (program, listing))
        loaded |= {m.group(1) for m in re.finditer(r"(\S+) => ", listing)}
    for name in os.listdir(lib):
        if name not in loaded and os.path.isfile(os.path.join(lib, name)):
            os.remove(os.path.join(lib, name))
            stubbed = [s for s in stubbed if s != name]
            kept = [k for k in kept if k != name]
    print("gpu-bundle: %d libraries kept, %d stubbed, into %s" % (len(kept), len(stubbed), out))


if __name__ == "__main__":
    main()
