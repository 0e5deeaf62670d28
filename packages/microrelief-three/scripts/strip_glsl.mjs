// strip_glsl.mjs: the GLSL scripts/build.mjs ships, made small without changing what any
// shader made from it compiles to (issue 48, "Small shaders": the library's comments were
// more than half of the package's bytes and of each relief shader's source).
//
//  * Comments go: a // comment to the end of its line, a /* */ comment becomes one space,
//    as the preprocessor itself replaces them, or the newlines it spanned (every token keeps
//    its line); on a directive's line (#define ...), which must stay one line, one space,
//    and the newlines after the directive.
//  * Functions no shader can call go, conservatively. GLSL's preprocessor decides which
//    functions a shader has under its #if branches, and the package joins these texts
//    with three's at run time, so a function is kept when its name appears anywhere
//    outside its own definitions (prototypes and bodies) in any of the texts stripped
//    together, under any #if branch, in any #define or #if expression, or in the package's
//    JavaScript (`roots`: every identifier of src/*.js, where the splices are written). The
//    test is repeated until nothing more goes (a function only a removed one called goes
//    too). Only whole definitions go, and only ones whose text is plain: nothing but
//    #if/#ifdef/#ifndef/#elif/#else/#endif inside them, balanced, none in their heads. A
//    text in which braces and #if branches are not nested in each other, that pastes tokens
//    (##), or whose macros hold braces keeps all its functions.
//  * Whitespace: each line trimmed, runs of spaces one space, empty lines dropped. A text
//    that has #line or __LINE__ keeps its line numbers (its emptied lines stay, empty).
//
// strip(texts, roots) takes {name: text} and returns {name: stripped} and the names of the
// functions removed; it throws Error (a /* comment never closed) naming the text.

const kKeywords = new Set(['if', 'for', 'while', 'switch', 'return', 'do', 'else', 'case', 'layout', 'struct', 'uniform', 'defined']);
const kConditionals = new Set(['if', 'ifdef', 'ifndef', 'elif', 'else', 'endif']);

// `text` without comments (see the header): every token stays on its line.
export function stripComments(text, name = 'GLSL') {
    let out = '', pending = '', directive = false, lineStart = true;
    for (let k = 0; k < text.length;) {
        const c = text[k], next = text[k + 1];
        if (lineStart) {
            directive = /^[ \t]*#/.test(text.slice(k, k + 256));
            lineStart = false;
        }
        if (c === '/' && next === '/') {
            k += 2;
            while (k < text.length && text[k] !== '\n') {
                if (text[k] === '\\' && text[k + 1] === '\n') {  // a continued // comment goes on
                    pending += '\n';
                    ++k;
                }
                ++k;
            }
            out += ' ';
        } else if (c === '/' && next === '*') {
            const end = text.indexOf('*/', k + 2);
            if (end < 0) throw new Error(`${name}: a /* comment is not closed`);
            const newlines = text.slice(k + 2, end).replace(/[^\n]/g, '');
            if (directive) {
                pending += newlines;
                out += ' ';
            } else {
                out += newlines || ' ';
            }
            k = end + 2;
        } else if (c === '\n') {
            // A backslash before the newline continues the line (and a directive).
            if (text[k - 1] === '\\') out += '\n';
            else {
                out += '\n' + pending;
                pending = '';
                lineStart = true;
            }
            ++k;
        } else {
            out += c;
            ++k;
        }
    }
    return out + pending;
}

// Each line trimmed, its runs of blanks one space, its empty lines dropped unless
// `keepLines`. A line after one that ends in a backslash keeps a leading space if it had one
// (the two are one line).
export function compact(text, keepLines) {
    const lines = text.split('\n');
    const out = [];
    let continued = false;
    for (const line of lines) {
        let l = line.replace(/[ \t\f\v\r]+/g, ' ');
        l = continued ? l.replace(/ +$/, '') : l.trim();
        if (continued && l === '' && !keepLines) l = ' ';
        continued = /\\$/.test(l);
        if (l !== '' || keepLines) out.push(l);
    }
    let result = out.join('\n');
    if (!keepLines) result = result.replace(/\n+$/, '');
    return result + (text.endsWith('\n') && !result.endsWith('\n') ? '\n' : '');
}

// The tokens of `text` that the function scan needs: identifiers, numbers and single
// characters, each with its offset and whether it is on a directive line (#...), and the
// directives themselves ({start, end, keyword, body}).
function scan(text) {
    const tokens = [], directives = [];
    const pattern = /[A-Za-z_]\w*|\d[\w.]*|\.\d[\w.]*|\S/g;
    let lineStart = 0;
    while (lineStart < text.length) {
        // A logical line: physical lines joined by a backslash before the newline.
        let end = text.indexOf('\n', lineStart);
        while (end >= 0 && text[end - 1] === '\\') end = text.indexOf('\n', end + 1);
        if (end < 0) end = text.length;
        const line = text.slice(lineStart, end);
        const directive = /^\s*#\s*(\w*)/.exec(line);
        if (directive) directives.push({start: lineStart, end, keyword: directive[1], body: line});
        for (const m of line.matchAll(pattern)) {
            if (m[0] === '\\') continue;
            tokens.push({text: m[0], at: lineStart + m.index, directive: Boolean(directive)});
        }
        lineStart = end + 1;
    }
    return {tokens, directives};
}

const isIdentifier = (t) => t !== undefined && /^[A-Za-z_]\w*$/.test(t.text);

// The functions of `text` that can be removed whole, by name: [{name, start, end}] (their
// definitions' and prototypes' offsets), and the names of those that cannot. null when the
// text's structure is not plain enough to cut anything out of it.
function functionsOf(text) {
    const {tokens, directives} = scan(text);
    if (directives.some((d) => /##|[{}]/.test(d.body))) return null;
    const code = tokens.filter((t) => !t.directive);
    // Braces matched; each token's scope (the innermost open brace's index, -1 at the top)
    // and the scope in force after it.
    const match = new Map();
    const open = [];
    for (let k = 0; k < code.length; ++k) {
        const t = code[k];
        t.scope = open.length ? open[open.length - 1] : -1;
        if (t.text === '{') open.push(k);
        else if (t.text === '}') {
            if (!open.length) return null;
            match.set(open.pop(), k);
        }
        t.scopeAfter = open.length ? open[open.length - 1] : -1;
    }
    if (open.length) return null;
    // The scope at a text offset: after the last code token before it.
    const scopeAt = (offset) => {
        let lo = 0, hi = code.length;
        while (lo < hi) {
            const mid = (lo + hi) >> 1;
            if (code[mid].at < offset) lo = mid + 1;
            else hi = mid;
        }
        return lo === 0 ? -1 : code[lo - 1].scopeAfter;
    };
    // Each #if's branches and its #endif within one pair of braces.
    const stack = [];
    for (const d of directives) {
        if (!kConditionals.has(d.keyword)) continue;
        const scope = scopeAt(d.start);
        if (d.keyword.startsWith('if')) stack.push(scope);
        else {
            if (!stack.length || stack[stack.length - 1] !== scope) return null;
            if (d.keyword === 'endif') stack.pop();
        }
    }
    if (stack.length) return null;

    const directiveBetween = (from, to) => directives.filter((d) => d.start < to && d.end > from);
    const found = [], fixed = new Set();
    for (let k = 1; k < code.length - 1; ++k) {
        const t = code[k];
        if (t.scope !== -1 || !isIdentifier(t) || kKeywords.has(t.text) || code[k + 1].text !== '(') continue;
        const before = code[k - 1];
        if (!(isIdentifier(before) && !kKeywords.has(before.text)) && before.text !== ']') continue;
        // The parameters' closing parenthesis, then '{' (a definition) or ';' (a prototype).
        let depth = 0, close = -1;
        for (let j = k + 1; j < code.length; ++j) {
            if (code[j].text === '(') ++depth;
            else if (code[j].text === ')' && --depth === 0) {
                close = j;
                break;
            } else if (code[j].text === ';' || code[j].text === '{' || code[j].text === '}') break;
        }
        if (close < 0) continue;
        const after = code[close + 1];
        if (!after || (after.text !== '{' && after.text !== ';')) continue;
        // The declaration's first token: after the last ';' or '}' (or the text's start) before it.
        let first = k - 1;
        while (first > 0 && code[first - 1].text !== ';' && code[first - 1].text !== '}') --first;
        const start = code[first].at;
        const last = after.text === '{' ? code[match.get(close + 1)] : after;
        const end = last.at + 1;
        const headDirectives = directiveBetween(start, after.at);
        const bodyDirectives = directiveBetween(after.at, end);
        const plain = headDirectives.length === 0 && bodyDirectives.every((d) => kConditionals.has(d.keyword));
        if (plain) found.push({name: t.text, start, end});
        else fixed.add(t.text);
        k = close + 1;
    }
    return {functions: found, fixed};
}

// How often each identifier appears in `text` (numbers' letters are no identifiers).
function identifierCounts(text) {
    const counts = new Map();
    for (const m of text.replace(/\b\d[\w.]*|\.\d[\w.]*/g, ' ').matchAll(/[A-Za-z_]\w*/g)) counts.set(m[0], (counts.get(m[0]) ?? 0) + 1);
    return counts;
}

// {name: text} with comments, unreachable functions and blanks stripped (see the header).
export function strip(texts, roots = new Set()) {
    let current = {};
    for (const [name, text] of Object.entries(texts)) current[name] = stripComments(text, name);
    const removed = new Set();
    for (;;) {
        const definedIn = new Map();  // function name -> [{part, start, end}]
        const fixed = new Set();
        for (const [name, text] of Object.entries(current)) {
            const f = functionsOf(text);
            if (!f) continue;
            for (const fn of f.functions) {
                if (!definedIn.has(fn.name)) definedIn.set(fn.name, []);
                definedIn.get(fn.name).push({part: name, ...fn});
            }
            for (const n of f.fixed) fixed.add(n);
        }
        // A candidate is used when its name appears outside its own definitions, in any
        // text (inside other functions too: those removed this round free theirs next round).
        const total = new Map();
        for (const text of Object.values(current))
            for (const [id, n] of identifierCounts(text)) total.set(id, (total.get(id) ?? 0) + n);
        const unused = [];
        for (const [fn, sites] of definedIn) {
            if (roots.has(fn) || fn === 'main' || fixed.has(fn)) continue;
            const own = sites.reduce((n, s) => n + (identifierCounts(current[s.part].slice(s.start, s.end)).get(fn) ?? 0), 0);
            if (total.get(fn) === own) unused.push(fn);
        }
        if (!unused.length) break;
        for (const fn of unused) removed.add(fn);
        for (const name of Object.keys(current)) {
            const cuts = unused.flatMap((fn) => definedIn.get(fn).filter((s) => s.part === name)).sort((a, b) => b.start - a.start);
            let text = current[name];
            for (const c of cuts) {
                // The lines it took stay as newlines (compact drops them where it may).
                text = text.slice(0, c.start) + text.slice(c.start, c.end).replace(/[^\n]/g, '') + text.slice(c.end);
            }
            current[name] = text;
        }
    }
    const out = {};
    for (const [name, text] of Object.entries(current)) out[name] = compact(text, /#\s*line\b|__LINE__/.test(text));
    return {texts: out, removed: [...removed].sort()};
}
