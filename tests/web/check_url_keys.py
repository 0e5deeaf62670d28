#!/usr/bin/env python3
"""The pages' URL keys are microrelief-render's flags (docs/browser.md, docs/three.md).

check_url_keys.py RENDER SOURCE_DIR

A page reads its view from the URL with get('key', ...) and offers a key's words with
choice('key', t, [...]); the web page also writes the command line that draws its view
(renderCommandLine: flag('--key', ...) and `--key=`). This check holds each against
microrelief-render itself: every key that is not one of a page's own is a flag its --help
lists, every word a page offers for a key is one the program takes (a 1x1 render with that
flag alone), every flag the command line writes is the program's, and every name the pages'
checks give a scene's field in a message (web/scene_checks.js: kFieldNames) is a key a page
reads, or, dashes and all, a flag of the program's. Where a key is a page's own (the
page's resolution, a clean picture, three's shading), tests/web/page_keys.txt lists it with
the reason (tests/docs/scene_field_table.cpp reads the same list); a word, below. A listed
key or word that is no longer in the page fails, so the lists cannot go stale. The web
page's lists of a choice the shader takes as a number (INDEXED) are the program's whole
lists, in the program's order: the order in which it names the choices when it refuses an
unknown word (its names tables, the enums' order). The numbers themselves come by name
from relief_layout.js (generated from shaders/microrelief/variants.glsl), not from a
position in these lists.
"""
import os
import re
import subprocess
import sys
import tempfile

# The pages whose URL keys are checked.
PAGES = ['web/scene.js', 'examples/three/view.js']
# Words that belong to a page, not to microrelief-render (its own keys: page_keys.txt).
# albedo=map is the bundled map's colours, which microrelief-render draws without --albedo.
PAGE_WORDS = {('albedo', 'map')}
# web/scene.js's lists of a choice that is a #define of relief.frag or a uniform (relief_gl.js:
# MICRORELIEF_METHOD, MICRORELIEF_SHADOWS, MICRORELIEF_INTERPOLATION, debugView), by key.
INDEXED = {'view': 'kViews', 'shadows': 'kShadows', 'interpolation': 'kInterpolations'}
# Keys whose words every page that offers the key offers all of, in any order: a page that
# writes the words by hand must name a base added to the program's table of bases
# (docs/bases.md, "Adding a base"); one that takes them from relief_core.js (CORE_LISTS) has
# them all.
WHOLE = {'base'}
# Word lists a page imports from web/relief_core.js, the browser's host core (the web page's
# './relief_core.js', examples/three's the package's copy, './node_modules/microrelief-three/
# generated/relief_core.js'), rather than writes: ctest web.core (tests/web/relief_core_test.mjs) holds each, name by name and in
# order, to the C++ table it mirrors, so this check takes them as read.
CORE_LISTS = {'kBaseNames': 'the table of bases (core/base/BaseType.h)'}
# Word lists a page takes from relief_layout.js, generated from the GLSL's rows that
# microrelief-render names its choices from too (cmake/generate_contracts.py): the same words
# in the same order by construction. The list -> what the page must import for it.
GENERATED_LISTS = {'kMethods': 'kMethodTraits'}


def fail(message):
    print(f'check_url_keys: {message}')
    sys.exit(1)


def page_keys(path):
    """The pages' own keys, page -> {key: why}, from page_keys.txt: a page, a key and the
    reason a line; '#' starts a comment line."""
    keys = {page: {} for page in PAGES}
    for number, line in enumerate(open(path, encoding='utf-8'), 1):
        if not line.strip() or line.lstrip().startswith('#'):
            continue
        fields = line.split(None, 2)
        if len(fields) < 3 or fields[0] not in keys:
            fail(f'{path}:{number}: not "PAGE KEY WHY" with PAGE one of {PAGES}: {line.strip()}')
        keys[fields[0]][fields[1]] = fields[2].strip()
    return keys


def words_of(text, expression, page, key, problems):
    """The words of a choice: a literal list, a constant list, or Object.keys of a constant."""
    if expression.startswith('['):
        return re.findall(r"'([^']*)'", expression)
    match = re.fullmatch(r'(?:Object\.keys\((\w+)\)|(\w+))', expression)
    name = match and (match.group(1) or match.group(2))
    found = name and re.search(r'const ' + name + r' = ([\[{][^\]}]*[\]}])', text)
    if not found:
        problems.append(f'{page}: the words of key {key} ({expression}) are not a list the check can read')
        return []
    body = found.group(1)
    if body.startswith('{'):
        return re.findall(r'(\w+)\s*:', body)
    return re.findall(r"'([^']*)'", body)


def program_choices(render, key, out, problems):
    """The words --key takes, in the order microrelief-render names them when it refuses an
    unknown one; None (a problem noted) where it names none."""
    run = subprocess.run([render, '-q', '--size', '1x1', f'--{key}', '-no-such-word-',
                          '--out', out], capture_output=True, text=True)
    named = re.search(r'\(expected (.*)\)', run.stderr)
    if not named:
        problems.append(f'--{key}: microrelief-render does not name its choices: {run.stderr.strip()}')
        return None
    return re.split(r', | or ', named.group(1))


def main():
    render, source = sys.argv[1], sys.argv[2]
    help_text = subprocess.run([render, '--help'], capture_output=True, text=True, check=True).stdout
    flags = set(re.findall(r'(--[a-z][a-z-]*)', help_text))
    if '--eye' not in flags:
        fail(f'{render} --help lists no --eye: not the program expected')
    problems = []
    words_to_try = set()
    offered_words = {}  # (page, key): the words the page offers for the key
    core_offered = set()  # (page, key): the page offers the key's words from relief_core.js
    own_keys = page_keys(os.path.join(source, 'tests', 'web', 'page_keys.txt'))
    for page, own in own_keys.items():
        text = open(os.path.join(source, page), encoding='utf-8').read()
        keys = set(re.findall(r"\bget\('([a-z][a-z-]*)'", text))
        if not keys:
            problems.append(f'{page}: no get(\'key\', ...) found: the check no longer reads the page')
        for key in sorted(keys):
            if key in own:
                continue
            if f'--{key}' not in flags:
                problems.append(f'{page}: URL key {key}: microrelief-render has no --{key}')
        for key in sorted(set(own) - keys):
            problems.append(f'{page}: {key} is listed as the page\'s own key but the page reads no such key')
        offered = 0
        for key, words in re.findall(r"choice\('([a-z][a-z-]*)', t, (\[[^\]]*\]|Object\.keys\(\w+\)|\w+)\)", text):
            if words in CORE_LISTS and re.search(r"import \{[^}]*\b" + words + r"\b[^}]*\} from '\./(?:node_modules/microrelief-three/generated/)?relief_core\.js'", text):
                offered += 1
                core_offered.add((page, key))
                continue
            if words in GENERATED_LISTS:
                source_list = GENERATED_LISTS[words]
                if not (re.search(r"import \{[^}]*\b" + source_list + r"\b[^}]*\} from './relief_layout\.js'", text)
                        and re.search(r'const ' + words + r' = Object\.keys\(' + source_list + r'\)', text)):
                    problems.append(f"{page}: {words} is not Object.keys({source_list}) from './relief_layout.js' "
                                    f"(the generated rows): a list written by hand drifts from microrelief-render's")
                offered += 1
                continue
            for word in words_of(text, words.strip(), page, key, problems):
                offered += 1
                offered_words.setdefault((page, key), []).append(word)
                if key not in own and (key, word) not in PAGE_WORDS:
                    words_to_try.add((key, word))
        if not offered:
            problems.append(f'{page}: no choice(\'key\', t, words) found: the check no longer reads the page')
        if page == 'web/scene.js':
            written = set(re.findall(r"flag\('(--[a-z-]+)'", text)) | set(re.findall(r'`(--[a-z-]+)=', text))
            if not written:
                problems.append(f'{page}: renderCommandLine writes no flag the check can find')
            for flag in sorted(written - flags):
                problems.append(f'{page}: renderCommandLine writes {flag}, which microrelief-render does not take')
    # The names the checks' messages give the fields: a page's key, or the program's flag.
    read_keys = set()
    for page in PAGES:
        read_keys |= set(re.findall(r"\bget\('([a-z][a-z-]*)'", open(os.path.join(source, page), encoding='utf-8').read()))
    checks = open(os.path.join(source, 'web/scene_checks.js'), encoding='utf-8').read()
    table = re.search(r'export const kFieldNames = \{([^}]*)\}', checks)
    names = re.findall(r":\s*'([^']*)'", table.group(1)) if table else []
    if not names:
        problems.append('web/scene_checks.js: no kFieldNames the check can read')
    for name in names:
        if name.startswith('--') and name not in flags:
            problems.append(f'web/scene_checks.js: kFieldNames names a field {name}, which microrelief-render does not take')
        elif not name.startswith('--') and name not in read_keys:
            problems.append(f'web/scene_checks.js: kFieldNames names a field {name}, a key no page reads')
    with tempfile.TemporaryDirectory() as scratch:
        out = os.path.join(scratch, 'x.png')
        scene = open(os.path.join(source, 'web/scene.js'), encoding='utf-8').read()
        for key, constant in INDEXED.items():
            found = re.search(r'const ' + constant + r" = \[([^\]]*)\]", scene)
            page_list = re.findall(r"'([^']*)'", found.group(1)) if found else []
            if not page_list:
                problems.append(f'web/scene.js: no list {constant} the check can read')
                continue
            program_list = program_choices(render, key, out, problems)
            if program_list is not None and page_list != program_list:
                problems.append(f'web/scene.js: {constant} is {page_list}; microrelief-render\'s --{key} '
                                f'takes {program_list}, in that order')
        for key in sorted(WHOLE):
            pages = sorted(page for (page, k) in offered_words if k == key)
            if not pages and not any(k == key for (_, k) in core_offered):
                problems.append(f'no page offers key {key}: the check no longer reads the pages')
                continue
            program_words = set(program_choices(render, key, out, problems) or [])
            for page in pages if program_words else []:
                missing = program_words - set(offered_words[(page, key)])
                if missing:
                    problems.append(f'{page}: key {key} does not offer {sorted(missing)}, which '
                                    f'microrelief-render --{key} takes')
        for key, word in sorted(words_to_try):
            run = subprocess.run([render, '-q', '--size', '1x1', f'--{key}', word, '--out', out],
                                 capture_output=True, text=True)
            if run.returncode != 0:
                problems.append(f'{key}={word}: microrelief-render --{key} {word} fails: {run.stderr.strip()}')
    if problems:
        fail('\n  '.join([f'{len(problems)} disagreement(s):'] + problems))
    print(f'check_url_keys: {len(flags)} flags; every key and word of the pages agrees '
          f'({len(words_to_try)} words rendered)')


if __name__ == '__main__':
    main()
