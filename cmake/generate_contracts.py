#!/usr/bin/env python3
"""generate_contracts.py: what C++, JavaScript and GLSL must agree on, generated from the
one place it is written, at build time (cmake/Contracts.cmake runs it; nothing it writes
is committed):

  * the uniform block MicroreliefParameters, written in shaders/relief_parameters.glsl:
    its std140 layout as a C++ struct with a static_assert on every member's offset
    (--struct) and as an ES module with the offsets and a writer (--js);
  * constants of the GLSL library that the C++ twin shares (--constants): each
    `#define NAME value` or `const type NAME = value;` named on the command line, read
    from the GLSL file that defines it, as a constexpr in C++ (--constants-header) and an
    export of the same ES module;
  * the enumerations that choose a shader variant or a uniform's meaning (--enums): each
    FILE:PREFIX:CppEnum, every `#define PREFIX_NAME value` (or `const int PREFIX_NAME =
    value;`) of FILE a member, values 0, 1, 2 ... in the file's order; in C++ a constexpr a
    member (glsl::kCppEnumName), the count, a table of names and values and an X-macro
    MICRORELIEF_GLSL_CPP_ENUM_MEMBERS(X), X(Name, name, value) a member (the same
    header), in JavaScript a frozen name -> value map (kCppEnumValues, the same module),
    keyed by the member's lower-case name (MR_METHOD_MAXMIP: 'maxmip');
  * the rows of an enumeration: an --enums spec FILE:PREFIX:CppEnum:TRAIT:ROW, every
    `#define TRAIT_NAME bit` of FILE a trait (distinct powers of two) and every `#define
    ROW_MEMBER (TRAIT_A | TRAIT_B ...)` the row of the member PREFIX_MEMBER (one for each
    member, no more); in C++ a constexpr a trait (glsl::kCppEnumTraitName) and the rows by
    value (glsl::kCppEnumTraits[]), in JavaScript the trait names of each member
    (kCppEnumTraits: {maxmip: ['solid', ...]}) and the traits' bits (kCppEnumTraitValues);
  * the named rows of an enumeration: an --enums spec FILE:PREFIX:CppEnum:@TAG, every
    comment line `//@TAG NAME MEMBER "summary"` of FILE a row (a name, the member of the
    enumeration it is, PREFIX_MEMBER, and a line of text), each `//@size FIELD "Label"
    SHAPE_MEMBER[WIDTH] = DEFAULTS [example NUMBERS]` under it one of its sizes (read_named
    says what each part means and what is refused); in C++ glsl::kTagRows[] (struct
    glsl::TagRow, its sizes glsl::TagSizeRow), in JavaScript kTagRows (the table of bases:
    @base, glsl::kBaseRows and kBaseRows).

Python 3 standard library only. A block or constant this script cannot read is an error
that names the file and the line, so the build stops rather than guess.
"""
import argparse
import ast
import operator
import pathlib
import re
import sys

# std140 (OpenGL 4.6 core, 7.6.2.2): base alignment and size in bytes of each type the
# block may hold; the C++ type that mirrors it, with glm's tight packing (alignof 4).
TYPES = {
    "float": (4, 4, "float", 1, "f32"),
    "int": (4, 4, "std::int32_t", 1, "i32"),
    "uint": (4, 4, "std::uint32_t", 1, "u32"),
    "vec2": (8, 8, "glm::vec2", 2, "f32"),
    "vec3": (16, 12, "glm::vec3", 3, "f32"),
    "vec4": (16, 16, "glm::vec4", 4, "f32"),
    "ivec2": (8, 8, "glm::ivec2", 2, "i32"),
    "ivec3": (16, 12, "glm::ivec3", 3, "i32"),
    "ivec4": (16, 16, "glm::ivec4", 4, "i32"),
    "mat4": (16, 64, "glm::mat4", 16, "f32"),
}


def fail(where, message):
    sys.exit(f"generate_contracts.py: error: {where}: {message}")


def read_block(path):
    """The members of the std140 uniform block in `path`: (type, name, comment, line)."""
    lines = pathlib.Path(path).read_text().splitlines()
    members, inside, name = [], False, None
    for number, line in enumerate(lines, 1):
        code = line.split("//", 1)[0].strip()
        comment = line.split("//", 1)[1].strip() if "//" in line else ""
        if not inside:
            m = re.match(r"layout\(std140\)\s+uniform\s+(\w+)\s*\{$", code)
            if m:
                inside, name = True, m.group(1)
            continue
        if code == "};":
            return name, members
        if not code:
            if comment and members:  # a comment that goes on from the member above
                members[-1][2] += " " + comment
            continue
        m = re.fullmatch(r"(\w+)\s+(\w+)\s*;", code)
        if not m:
            fail(f"{path}:{number}", f"not a member this generator reads: '{code}' (one 'type name;' a line)")
        if m.group(1) not in TYPES:
            fail(f"{path}:{number}", f"type {m.group(1)} is not one the generator lays out ({', '.join(TYPES)})")
        members.append([m.group(1), m.group(2), comment, number])
    fail(path, "no 'layout(std140) uniform NAME {' ... '};' block")


def layout(members):
    """std140 offsets, and the block's size (a multiple of 16)."""
    offset, placed = 0, []
    for type_, name, comment, line in members:
        align, size = TYPES[type_][0], TYPES[type_][1]
        offset = (offset + align - 1) // align * align
        placed.append((type_, name, comment, line, offset))
        offset += size
    return placed, (offset + 15) // 16 * 16


def cpp_struct(block, placed, size, source):
    out = [
        f"// Generated from {source} by cmake/generate_contracts.py: do not edit; edit the block.",
        f"// {block}, std140, as a C++ struct: what ReliefShader's programs read from uniform",
        "// buffer binding 0. Members are value-initialised (matrices to the identity); explicit",
        "// padding keeps every member at its std140 offset, which the asserts below hold.",
        "#pragma once",
        "",
        "#include <cstddef>",
        "#include <cstdint>",
        "",
        "#include <glm/glm.hpp>",
        "",
        "namespace microrelief {",
        "",
        "struct ReliefParameters {",
    ]
    natural, pads = 0, 0
    for type_, name, comment, line, offset in placed:
        if offset > natural:
            out.append(f"    std::uint8_t padding{pads}_[{offset - natural}] = {{}};")
            pads += 1
        cpp = TYPES[type_][2]
        init = "{1.0f}" if type_ == "mat4" else "{}"
        text = f"    {cpp} {name}{init};"
        out.append(f"{text}  // {comment}" if comment else text)
        natural = offset + TYPES[type_][1]
    if size > natural:
        out.append(f"    std::uint8_t padding{pads}_[{size - natural}] = {{}};")
    out += ["};", "", f'static_assert(sizeof(ReliefParameters) == {size}, "std140 size of {block}");']
    for type_, name, comment, line, offset in placed:
        out.append(f"static_assert(offsetof(ReliefParameters, {name}) == {offset});")
    out += ["", "// Every member's name and std140 offset, in order: what a test holds the linked program to.",
            "struct ReliefParameterMember {", "    const char* name;", "    std::size_t offset;", "};",
            "inline constexpr ReliefParameterMember kReliefParameterMembers[] = {"]
    for type_, name, comment, line, offset in placed:
        out.append(f'    {{"{name}", {offset}}},')
    out += ["};", "", "}  // namespace microrelief", ""]
    return "\n".join(out)


OPERATORS = {ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul, ast.Div: operator.truediv}


def evaluate(expression, where):
    """A constant's value: numbers and + - * / only."""
    def value(node):
        if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)):
            return node.value
        if isinstance(node, ast.BinOp) and type(node.op) in OPERATORS:
            return OPERATORS[type(node.op)](value(node.left), value(node.right))
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub):
            return -value(node.operand)
        fail(where, f"'{expression}' is not a number or arithmetic of numbers")
    return value(ast.parse(expression.replace("u", ""), mode="eval").body)


def read_constant(shaders, spec):
    """(C++ name, GLSL name, value, is it an integer, where) of FILE:NAME:cppName."""
    file, name, cpp = spec.split(":")
    path = pathlib.Path(shaders) / file
    for number, line in enumerate(path.read_text().splitlines(), 1):
        m = re.match(rf"\s*#\s*define\s+{name}\s+(.+?)\s*(//.*)?$", line) or re.match(
            rf"\s*const\s+(?:highp\s+)?(?:float|int|uint)\s+{name}\s*=\s*(.+?);\s*(//.*)?$", line)
        if m:
            where = f"{path}:{number}"
            text = m.group(1)
            integer = re.fullmatch(r"-?\d+u?", text) is not None
            return cpp, name, evaluate(text, where), integer, f"{file}:{number}", text
    fail(path, f"defines no {name} (#define {name} ... or const ... {name} = ...;)")


def read_enum(shaders, spec):
    """(C++ enum name, prefix, file, [(NAME, value, line)]) of FILE:PREFIX:CppEnum (and
    FILE:PREFIX:CppEnum:TRAIT:ROW, whose rows read_rows reads, and FILE:PREFIX:CppEnum:@TAG,
    whose named rows read_named reads)."""
    if spec.count(":") not in (2, 3, 4) or (spec.count(":") == 3 and not re.fullmatch(r"@[a-z]+", spec.split(":")[3])):
        fail("--enums", f"'{spec}' is none of FILE:PREFIX:CppEnum, FILE:PREFIX:CppEnum:@TAG "
                        "and FILE:PREFIX:CppEnum:TRAIT:ROW")
    file, prefix, cpp = spec.split(":")[:3]
    path = pathlib.Path(shaders) / file
    members = []
    for number, line in enumerate(path.read_text().splitlines(), 1):
        m = re.match(rf"\s*#\s*define\s+{prefix}_(\w+)\s+(\S+)\s*(//.*)?$", line) or re.match(
            rf"\s*const\s+int\s+{prefix}_(\w+)\s*=\s*(\S+?)\s*;\s*(//.*)?$", line)
        if not m:
            continue
        where = f"{path}:{number}"
        if not re.fullmatch(r"\d+", m.group(2)):
            fail(where, f"{prefix}_{m.group(1)} is '{m.group(2)}', not a plain non-negative integer")
        if not re.fullmatch(r"[A-Z][A-Z0-9_]*", m.group(1)):
            fail(where, f"{prefix}_{m.group(1)}: a member's name is upper case")
        value = int(m.group(2))
        if value != len(members):
            # The C++ enums count from 0 in steps of 1 (ReliefShader.cpp casts them), so the
            # GLSL does too: a gap or a repeat is a slip, not a choice.
            fail(where, f"{prefix}_{m.group(1)} is {value}; member {len(members) + 1} of {prefix}_* "
                        f"must be {len(members)} (values 0, 1, 2 ... in the file's order)")
        members.append((m.group(1), value, number))
    if not members:
        fail(path, f"defines no {prefix}_* (#define {prefix}_NAME value)")
    return cpp, prefix, file, members


def read_rows(shaders, spec, members):
    """(C++ enum name, trait prefix, row prefix, file, [(TRAIT, bit, line)], {MEMBER: (bits,
    [TRAIT], line)}, members) of FILE:PREFIX:CppEnum:TRAIT:ROW, the enumeration's `members`
    as read_enum read them."""
    file, _, cpp, trait_prefix, row_prefix = spec.split(":")
    path = pathlib.Path(shaders) / file
    traits, rows = [], {}
    for number, line in enumerate(path.read_text().splitlines(), 1):
        where = f"{path}:{number}"
        m = re.match(rf"\s*#\s*define\s+{trait_prefix}_(\w+)\s+(\S+)\s*(//.*)?$", line)
        if m:
            if not re.fullmatch(r"\d+", m.group(2)):
                fail(where, f"{trait_prefix}_{m.group(1)} is '{m.group(2)}', not a plain positive integer")
            bit = int(m.group(2))
            if bit <= 0 or bit & (bit - 1) or any(bit == b for _, b, _ in traits):
                fail(where, f"{trait_prefix}_{m.group(1)} is {bit}: each trait is a power of two of its own")
            traits.append((m.group(1), bit, number))
            continue
        m = re.match(rf"\s*#\s*define\s+{row_prefix}_(\w+)\s+(.+?)\s*(//.*)?$", line)
        if not m:
            continue
        member, text = m.group(1), m.group(2)
        if member not in [name for name, _, _ in members]:
            fail(where, f"{row_prefix}_{member} is the row of no member of {cpp}")
        if member in rows:
            fail(where, f"{row_prefix}_{member} is defined twice")
        body = text[1:-1] if text.startswith("(") and text.endswith(")") else text
        names = [] if body.strip() == "0" else [part.strip() for part in body.split("|")]
        known = {f"{trait_prefix}_{name}": (name, bit) for name, bit, _ in traits}
        for name in names:
            if name not in known:
                fail(where, f"{row_prefix}_{member}: '{name}' is not a {trait_prefix}_* defined above it")
        rows[member] = (sum(known[n][1] for n in names), [known[n][0] for n in names], number)
    if not traits:
        fail(path, f"defines no {trait_prefix}_* (#define {trait_prefix}_NAME bit)")
    missing = [name for name, _, _ in members if name not in rows]
    if missing:
        fail(path, f"no row for {', '.join(row_prefix + '_' + n for n in missing)} (#define {row_prefix}_NAME (TRAITS))")
    return cpp, trait_prefix, row_prefix, file, traits, rows, members


NUMBER = r"(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?"
MOST_NUMBERS = 3  # a size is at most three numbers (BaseType.h: the C++ reads them into double[3])


def read_named(shaders, spec, members):
    """The named rows of FILE:PREFIX:CppEnum:@TAG, the enumeration's `members` as read_enum
    read them: (C++ enum name, tag, file, first line, last line, [row]), a row {name, kind
    (the member's NAME), value, summary, line, sizes: [{field, label, member, width, count,
    defaults, example, line}]}, in the file's order.

    A row is a comment line `//@TAG NAME KIND "summary"`: NAME lower case, KIND a member of
    the enumeration (PREFIX_KIND), the summary one line without quotes or backslashes. Each
    `//@size FIELD "Label" MEMBER = DEFAULTS` (or MEMBER[WIDTH] for a member of WIDTH
    numbers, and `example NUMBERS` after the defaults) under it is one of its sizes: FIELD
    the scene's (base.radius), the label a slider's, MEMBER the shape's member it sets, the
    defaults positive numbers, as many as the member has or one that sets them all; a row
    with such a size names only the shapes whose member has equal numbers (the sphere), a
    row without one every shape of its kind that no such row takes. Refused, with the line:
    a tagged line of another form, a size above every row, a name twice, a kind that is not
    a member, a field twice in a row or with two counts, a member twice in a row or with two
    widths, a number that is not positive, an example of another count; and, with the file,
    a member of the enumeration that is no row's general kind, or two such rows, or two
    rows that name the same shapes."""
    file, prefix, cpp, tag = spec.split(":")
    tag = tag[1:]
    path = pathlib.Path(shaders) / file
    kinds = {name: value for name, value, _ in members}
    rows, lines = [], []
    for number, line in enumerate(path.read_text().splitlines(), 1):
        where = f"{path}:{number}"
        m = re.match(r"\s*//\s*@(\w*)(.*)$", line)
        if not m:
            continue
        lines.append(number)
        if m.group(1) == tag:
            r = re.fullmatch(rf'//@{tag}\s+(\S+)\s+(\S+)\s+"([^"\\]*)"\s*', line.strip())
            if not r:
                fail(where, f'not a row this generator reads (//@{tag} NAME KIND "summary")')
            name, kind, summary = r.groups()
            if not re.fullmatch(r"[a-z][a-z0-9_]*", name):
                fail(where, f"//@{tag} {name}: a name is lower case (letters, digits, _)")
            if any(row["name"] == name for row in rows):
                fail(where, f"//@{tag} {name}: the name is a row's above")
            if kind not in kinds:
                fail(where, f"//@{tag} {name}: '{kind}' is not a member of {prefix}_* ({', '.join(kinds)})")
            if not summary.strip():
                fail(where, f"//@{tag} {name}: the summary is empty")
            rows.append({"name": name, "kind": kind, "value": kinds[kind], "summary": summary, "line": number,
                         "sizes": []})
        elif m.group(1) == "size":
            r = re.fullmatch(r'//@size\s+(\S+)\s+"([^"\\]*)"\s+([A-Za-z_]\w*)(?:\[(\d+)\])?\s*=\s*(.*?)'
                             r'(?:\s+example\s+(.*?))?\s*', line.strip())
            if not r:
                fail(where, 'not a size this generator reads (//@size FIELD "Label" MEMBER[WIDTH] = NUMBERS '
                            '[example NUMBERS])')
            if not rows:
                fail(where, f"a size above every row (//@{tag} NAME KIND \"summary\" first)")
            field, label, member, width, defaults, example = r.groups()
            row = rows[-1]
            what = f"//@size {field} of {row['name']}"
            if not re.fullmatch(r"[a-z]+\.[a-z][A-Za-z0-9]*", field):
                fail(where, f"{what}: a field is the scene's, 'group.name' (base.minorRadius)")
            if not label.strip():
                fail(where, f"{what}: the label is empty")
            width = 1 if width is None else int(width)
            if not 1 <= width <= MOST_NUMBERS:
                fail(where, f"{what}: {member}[{width}]: a member is 1 to {MOST_NUMBERS} numbers")

            def numbers(text, part):
                parts = text.split()
                if not parts or not all(re.fullmatch(NUMBER, p) for p in parts):
                    fail(where, f"{what}: its {part} '{text}' is not numbers (1, 0.35, 2e3), blank-separated")
                values = [float(p) for p in parts]
                if any(not v > 0 or v == float("inf") for v in values):
                    fail(where, f"{what}: its {part} '{text}': a size is positive and finite")
                return values
            defaults = numbers(defaults, "defaults")
            count = len(defaults)
            if count not in (1, width):
                fail(where, f"{what}: {count} defaults for {member}[{width}] (1, which sets every number, or {width})")
            example = numbers(example, "example") if example is not None else list(defaults)
            if len(example) != count:
                fail(where, f"{what}: its example is {len(example)} numbers, its defaults {count}")
            if any(size["field"] == field for size in row["sizes"]):
                fail(where, f"{what}: the row has the field above")
            if any(size["member"] == member for size in row["sizes"]):
                fail(where, f"{what}: the row sets {member} above")
            for other in rows:
                for size in other["sizes"]:
                    if size["field"] == field and size["count"] != count:
                        fail(where, f"{what}: {count} numbers, where {other['name']}'s {field} is "
                                    f"{size['count']} (a field has one count: one flag)")
                    if size["member"] == member and size["width"] != width:
                        fail(where, f"{what}: {member}[{width}], where {other['name']}'s is "
                                    f"{member}[{size['width']}] (a member has one width)")
            row["sizes"].append({"field": field, "label": label, "member": member, "width": width, "count": count,
                                 "defaults": defaults, "example": example, "line": number})
        else:
            fail(where, f"'//@{m.group(1)}' is not a tag of {file} (//@{tag}, //@size)")
    if not rows:
        fail(path, f"defines no //@{tag} row")
    # Which shapes a row names: the members its sizes set all at once (one number for three).
    general, named = {}, {}
    for row in rows:
        row["equal"] = [size["member"] for size in row["sizes"] if size["count"] < size["width"]]
        if not row["equal"]:
            if row["kind"] in general:
                fail(path, f"rows {general[row['kind']]['name']} and {row['name']} both name every {row['kind']} "
                           f"(one row a kind takes every shape that no narrower row takes)")
            general[row["kind"]] = row
        else:
            key = (row["kind"], tuple(sorted(row["equal"])))
            if key in named:
                fail(path, f"rows {named[key]['name']} and {row['name']} name the same shapes of {row['kind']}")
            named[key] = row
    missing = [kind for kind in kinds if kind not in general]
    if missing:
        fail(path, f"no //@{tag} row takes every shape of {', '.join(missing)} (a row whose sizes set each "
                   "member whole)")
    return cpp, tag, file, lines[0], lines[-1], rows


def c_string(text):
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


def js_string(text):
    return "'" + text.replace("\\", "\\\\").replace("'", "\\'") + "'"


def cpp_named(all_named):
    out = []
    for cpp, tag, file, first, last, rows in all_named:
        Tag = tag.capitalize()
        most = max(1, max(len(row["sizes"]) for row in rows))
        out += [
            "",
            f"// //@{tag} and //@size ({file}:{first}-{last}): the named rows of {cpp}, in order, each",
            f"// with its sizes (what core/base/BaseTable.cpp builds the table from).",
            f"struct {Tag}SizeRow {{",
            "    const char* field;     // the scene's field",
            "    const char* label;     // a slider's",
            "    const char* member;    // the shape's member it sets",
            "    int memberWidth;       // how many numbers the member holds",
            "    int count;             // how many the size is: memberWidth, or 1 for all of them",
            f"    double defaults[{MOST_NUMBERS}];    // its first `count` numbers",
            f"    double example[{MOST_NUMBERS}];",
            "};",
            f"inline constexpr int k{Tag}MostSizes = {most};",
            f"struct {Tag}Row {{",
            "    const char* name;",
            f"    int kind;  // the member of {cpp}",
            "    const char* summary;",
            "    int sizeCount;",
            f"    {Tag}SizeRow sizes[k{Tag}MostSizes];",
            "};",
            f"inline constexpr {Tag}Row k{Tag}Rows[] = {{",
        ]

        def numbers(values):
            return "{" + ", ".join(repr(float(v)) for v in values) + "}"
        for row in rows:
            out.append(f"    {{{c_string(row['name'])}, k{cpp}{camel(row['kind'])}, {c_string(row['summary'])}, "
                       f"{len(row['sizes'])},  // {file}:{row['line']}")
            sizes = [f"{{{c_string(s['field'])}, {c_string(s['label'])}, {c_string(s['member'])}, {s['width']}, "
                     f"{s['count']}, {numbers(s['defaults'])}, {numbers(s['example'])}}}" for s in row["sizes"]]
            out.append("     {" + ",\n      ".join(sizes) + "}},")
        out += ["};", f"inline constexpr int k{Tag}RowCount = {len(rows)};"]
    return out


def js_named(all_named):
    out = []
    for cpp, tag, file, first, last, rows in all_named:
        Tag = tag.capitalize()
        out += [
            "",
            f"// The named rows of {cpp} (//@{tag} and //@size, {file}:{first}-{last}), in order: each",
            f"// row's name, kind (a key of k{cpp}Values), summary and sizes (the scene's field, a",
            "// slider's label, the shape's member it sets and how many numbers that member holds, how",
            "// many the size is, 1 for all of them, its defaults and the example a list offers).",
            f"export const k{Tag}Rows = Object.freeze([",
        ]

        def numbers(values):
            return "Object.freeze([" + ", ".join(repr(float(v)).removesuffix(".0") for v in values) + "])"
        for row in rows:
            sizes = [f"Object.freeze({{field: {js_string(s['field'])}, label: {js_string(s['label'])}, "
                     f"member: {js_string(s['member'])}, memberWidth: {s['width']}, count: {s['count']}, "
                     f"defaults: {numbers(s['defaults'])}, example: {numbers(s['example'])}}})" for s in row["sizes"]]
            out.append(f"    Object.freeze({{name: {js_string(row['name'])}, kind: {js_string(row['kind'].lower())}, "
                       f"summary: {js_string(row['summary'])}, sizes: Object.freeze([" +
                       "".join(f"\n        {size}," for size in sizes) + ("\n    " if sizes else "") + "])}),")
        out.append("]);")
    return out

def camel(name):
    return "".join(part.capitalize() for part in name.lower().split("_"))


def snake(cpp):
    """BaseKind: BASE_KIND."""
    return re.sub(r"(?<!^)(?=[A-Z])", "_", cpp).upper()


def cpp_enums(enums):
    if not enums:
        return []
    out = [
        "",
        "// The enumerations that choose a shader variant (a host's #define) or a uniform's",
        "// meaning, each member as a constant, their count, and their names (the programs' words)",
        "// with their values, in order.",
        "struct EnumMember {",
        "    const char* name;",
        "    int value;",
        "};",
    ]
    for cpp, prefix, file, members in enums:
        out += ["", f"// {prefix}_* ({file}:{members[0][2]}-{members[-1][2]}): {cpp}."]
        for name, value, line in members:
            out.append(f"inline constexpr int k{cpp}{camel(name)} = {value};")
        out.append(f"inline constexpr int k{cpp}Count = {len(members)};")
        out.append(f"inline constexpr EnumMember k{cpp}Values[] = {{")
        for name, value, line in members:
            out.append(f'    {{"{name.lower()}", {value}}},')
        out.append("};")
        # The members as an X-macro, X(Name, name, value) each in order (MR_BASE_FOO_BAR:
        # FooBar, fooBar, 3), so that C++ can spell an enumeration or a list of them from
        # the GLSL: BaseShape.h's BaseKind and BaseTable.cpp's kinds' geometry.
        macro = f"MICRORELIEF_GLSL_{snake(cpp)}_MEMBERS"
        out.append(f"// {macro}(X): X(Name, name, value) for each member of {prefix}_*, in order.")
        out.append(f"#define {macro}(X) \\")
        for name, value, line in members:
            Name = camel(name)
            out.append(f"    X({Name}, {Name[0].lower() + Name[1:]}, {value}) \\")
        out.append(f"    /* {file}:{members[0][2]}-{members[-1][2]} */")
    return out


def cpp_rows(all_rows):
    out = []
    for cpp, trait_prefix, row_prefix, file, traits, rows, members in all_rows:
        out += ["", f"// {trait_prefix}_* ({file}:{traits[0][2]}-{traits[-1][2]}): what a {cpp} is, one bit each."]
        for name, bit, line in traits:
            out.append(f"inline constexpr unsigned k{cpp}Trait{camel(name)} = {bit}u;")
        out.append(f"// {row_prefix}_* ({file}): each {cpp}'s traits, by its value.")
        out.append(f"inline constexpr unsigned k{cpp}Traits[] = {{")
        for name, value, line in members:
            bits, names, row_line = rows[name]
            out.append(f"    {bits}u,  // {name.lower()}: {' | '.join(n.lower() for n in names) or 'none'}")
        out.append("};")
    return out


def cpp_constants(constants, enums=(), rows=(), named=()):
    out = [
        "// Generated by cmake/generate_contracts.py from the GLSL library: do not edit; edit the",
        "// GLSL. The constants the C++ twin (trace/, base/) shares with the shaders, each the",
        "// value its GLSL file gives.",
        "#pragma once",
        "",
        "namespace microrelief::glsl {",
        "",
    ]
    for cpp, name, value, integer, where, text in constants:
        out.append(f"// {name} ({where}): {text}")
        out.append(f"inline constexpr int {cpp} = {int(value)};" if integer
                   else f"inline constexpr double {cpp} = {float(value)!r};")
    out += cpp_enums(enums)
    out += cpp_rows(rows)
    out += cpp_named(named)
    out += ["", "}  // namespace microrelief::glsl", ""]
    return "\n".join(out)


def js_module(block, placed, size, constants, source, enums=(), all_rows=(), named=()):
    out = [
        f"// Generated from {source} and the GLSL library by cmake/generate_contracts.py: do not",
        f"// edit. The uniform block {block} (std140), the library's shared constants and the",
        "// enumerations that choose a shader variant, for the page, microrelief-three and any",
        "// JavaScript host that fills the block or sets the #defines.",
        "",
        f"export const kParametersBlock = '{block}';",
        f"export const kParametersSize = {size};",
        "",
        "// Each member: its byte offset, its GLSL type, how many 32-bit components, and their kind.",
        "export const kParameters = Object.freeze({",
    ]
    for type_, name, comment, line, offset in placed:
        count, kind = TYPES[type_][3], TYPES[type_][4]
        out.append(f"    {name}: Object.freeze({{offset: {offset}, type: '{type_}', count: {count}, kind: '{kind}'}}),")
    out += [
        "});",
        "",
        "// The block's bytes for `values` (member name -> a number or an array of them; a matrix",
        "// in column-major order). Every member must be given (a member the host forgot would",
        "// read 0 in the shader, silently); a name that is not a member, or the wrong number of",
        "// components, is an error too.",
        "export function writeParameters(values) {",
        "    const missing = Object.keys(kParameters).filter((name) => !Object.hasOwn(values, name));",
        "    if (missing.length) throw new Error(`${kParametersBlock}: no value for ${missing.join(', ')}`);",
        "    const buffer = new ArrayBuffer(kParametersSize);",
        "    const view = new DataView(buffer);",
        "    for (const [name, value] of Object.entries(values)) {",
        "        const member = kParameters[name];",
        "        if (!member) throw new Error(`${kParametersBlock} has no member ${name}`);",
        "        const components = typeof value === 'number' || typeof value === 'boolean' ? [Number(value)] : Array.from(value);",
        "        if (components.length !== member.count) {",
        "            throw new Error(`${kParametersBlock}.${name}: ${member.count} components, not ${components.length}`);",
        "        }",
        "        components.forEach((c, k) => {",
        "            const at = member.offset + 4 * k;",
        "            if (member.kind === 'f32') view.setFloat32(at, c, true);",
        "            else if (member.kind === 'i32') view.setInt32(at, c, true);",
        "            else view.setUint32(at, c, true);",
        "        });",
        "    }",
        "    return buffer;",
        "}",
        "",
        "// The GLSL library's constants that hosts share (each with its file and line).",
    ]
    for cpp, name, value, integer, where, text in constants:
        out.append(f"export const {cpp} = {int(value) if integer else float(value)!r};  // {name}, {where}")
    if enums:
        out += [
            "",
            "// The enumerations that choose a shader variant (the value a host gives the #define)",
            "// or a uniform's meaning: each a name -> value map, the names the programs' words.",
        ]
    for cpp, prefix, file, members in enums:
        body = ", ".join(f"{name.lower()}: {value}" for name, value, line in members)
        out.append(f"export const k{cpp}Values = Object.freeze({{{body}}});  // {prefix}_*, {file}:{members[0][2]}")
    for cpp, trait_prefix, row_prefix, file, traits, rows, members in all_rows:
        body = ", ".join(f"{name.lower()}: {bit}" for name, bit, line in traits)
        out += ["", f"// What a {cpp} is ({trait_prefix}_*, {file}:{traits[0][2]}) and each one's traits ({row_prefix}_*)."]
        out.append(f"export const k{cpp}TraitValues = Object.freeze({{{body}}});")
        out.append(f"export const k{cpp}Traits = Object.freeze({{")
        for name, value, line in members:
            names = ", ".join(f"'{n.lower()}'" for n in rows[name][1])
            out.append(f"    {name.lower()}: Object.freeze([{names}]),")
        out.append("});")
    out += js_named(named)
    if enums:
        out += [
            "",
            "// The value of `name` in `values` (one of the maps above) as a #define's text, for the",
            "// macro `macro`; a name the map does not hold is an error that names both (a page's",
            "// list out of step with the GLSL), never the text 'undefined'.",
            "export function defineValue(values, name, macro) {",
            "    if (!Object.hasOwn(values, name)) throw new Error(`${macro}: no value for '${name}' (${Object.keys(values).join(', ')})`);",
            "    return String(values[name]);",
            "}",
        ]
    out.append("")
    return "\n".join(out)


def write_if_changed(path, text):
    """Writes `text` to `path` unless it holds it already (so that nothing rebuilds for an
    unchanged contract), through a temporary file and a rename."""
    path = pathlib.Path(path)
    if path.exists() and path.read_text() == text:
        return
    path.parent.mkdir(parents=True, exist_ok=True)
    temporary = path.with_name(f".{path.name}.tmp")
    temporary.write_text(text)
    temporary.replace(path)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--block", required=True, help="the GLSL file holding the uniform block")
    parser.add_argument("--shaders", required=True, help="shaders/microrelief, where --constants' files are")
    parser.add_argument("--constants", nargs="*", default=[], help="FILE:GLSL_NAME:CppName, each")
    parser.add_argument("--enums", nargs="*", default=[], help="FILE:PREFIX:CppEnum, FILE:PREFIX:CppEnum:@TAG or FILE:PREFIX:CppEnum:TRAIT:ROW, each")
    parser.add_argument("--struct", help="the C++ header of the block to write")
    parser.add_argument("--constants-header", help="the C++ header of the constants and enumerations to write")
    parser.add_argument("--js", required=True, help="the ES module to write; - for stdout")
    args = parser.parse_args()
    source = pathlib.Path(args.block).name
    block, members = read_block(args.block)
    placed, size = layout(members)
    constants = [read_constant(args.shaders, spec) for spec in args.constants]
    enums = [read_enum(args.shaders, spec) for spec in args.enums]
    rows = [read_rows(args.shaders, spec, enum[3]) for spec, enum in zip(args.enums, enums)
            if spec.count(":") == 4]
    named = [read_named(args.shaders, spec, enum[3]) for spec, enum in zip(args.enums, enums)
             if spec.count(":") == 3]
    if args.struct:
        write_if_changed(args.struct, cpp_struct(block, placed, size, source))
    if args.constants_header:
        write_if_changed(args.constants_header, cpp_constants(constants, enums, rows, named))
    module = js_module(block, placed, size, constants, source, enums, rows, named)
    if args.js == "-":
        sys.stdout.write(module)
    else:
        write_if_changed(args.js, module)


if __name__ == "__main__":
    main()
