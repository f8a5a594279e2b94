#!/usr/bin/env python3
"""The documentation against the program (ctest `docs`; Python 3, standard library only).

usage: check_docs.py SOURCE_DIR HAPSCENE_BINARY

Reads README.md, scripts/README.md and docs/**/*.md and checks:
  - links: every relative link and image resolves to a file, and every #anchor to a
    heading of the target page, as GitHub and mkdocs both name it;
  - ```json blocks that are whole environments (an object with "effects", or one such
    object a line) load: `hapscene probe FILE` at one point (exit 0);
  - ```lua blocks that are whole scripts (they define force) load the same way, in a 1-D
    environment, or in a planar one when the script is 2-D;
  - every `hapscene` command line in ```sh and ```console blocks is parsed by the real
    binary: an unknown command or option, an option given twice or without its value
    fails (the line is given an extra unknown option, which must be the one refused);
  - the commands of README.md's "first environment" and of docs/tutorials/ are run, in
    order, in a scratch folder (environments/ and scripts/ linked in, build/hapscene the
    binary), and where a ```console block shows output after `$ command`, the output is
    compared line by line (a line `...` stands for any lines);
  - README.md's "first environment" and docs/index.md's are the same text;
  - mkdocs.yml's nav lists every page of docs/;
  - every docs/*.md page the sources name (comments, messages, schemas) exists, and no
    source points into a README section any more (the sections are pages under docs/).

Conventions, written as an HTML comment on the line before a fenced block:
  <!-- no-test: REASON -->  the block is not run or loaded (hardware, another repository);
                            its command lines are still parsed
  <!-- file: NAME -->       the block is written to NAME in the scratch folder, for the
                            commands after it
  <!-- exit: N -->          the block's commands exit with N (default 0)
"""
import json
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
import unicodedata

SOURCE, BINARY = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
SENTINEL = '--zz-docs-parse-check'
failures = []
counts = {'links': 0, 'json': 0, 'lua': 0, 'parsed': 0, 'run': 0}


def fail(where, message):
    failures.append('%s: %s' % (where, message))


def markdown_files():
    files = [os.path.join(SOURCE, 'README.md'), os.path.join(SOURCE, 'scripts', 'README.md')]
    for folder, _, names in sorted(os.walk(os.path.join(SOURCE, 'docs'))):
        files += [os.path.join(folder, n) for n in sorted(names) if n.endswith('.md')]
    return files


# ---- reading a page: prose lines and fenced blocks with their directives ----
class Block:
    def __init__(self, lang, start, lines, directives):
        self.lang, self.start, self.lines, self.directives = lang, start, lines, directives


def parse(path):
    text = open(path, encoding='utf-8').read().split('\n')
    prose, blocks, i = [], [], 0
    while i < len(text):
        m = re.match(r'^(\s*)```(\S*)', text[i])
        if m:
            directives, k = {}, len(prose) - 1
            while k >= 0 and prose[k][1].strip().startswith('<!--'):
                d = re.match(r'<!--\s*([\w-]+):?\s*(.*?)\s*-->', prose[k][1].strip())
                if d:
                    directives[d.group(1)] = d.group(2)
                k -= 1
            start, body, i = i + 1, [], i + 1
            while i < len(text) and not text[i].strip().startswith('```'):
                body.append(text[i][len(m.group(1)):])
                i += 1
            blocks.append(Block(m.group(2), start, body, directives))
        else:
            prose.append((i + 1, text[i]))
        i += 1
    return prose, blocks


# ---- links and anchors ----
def slug_github(heading):
    text = re.sub(r'\[([^\]]*)\]\([^)]*\)', r'\1', heading).strip().lower()
    text = re.sub(r'[^\w\- ]', '', text)
    return text.replace(' ', '-')


def slug_mkdocs(heading):
    text = re.sub(r'\[([^\]]*)\]\([^)]*\)', r'\1', heading).replace('`', '')
    text = unicodedata.normalize('NFKD', text).encode('ascii', 'ignore').decode('ascii')
    text = re.sub(r'[^\w\s-]', '', text).strip().lower()
    return re.sub(r'[-\s]+', '-', text)


def anchors(path, style):
    prose, _ = parse(path)
    return {style(re.sub(r'^#+\s+', '', line)) for _, line in prose if re.match(r'^#{1,6}\s', line)}


def check_links(path):
    prose, _ = parse(path)
    for number, line in prose:
        line = re.sub(r'`[^`]*`', '', line)
        for target in re.findall(r'!?\[[^\]]*\]\(([^)\s]+)\)', line):
            if re.match(r'^[a-z]+:', target):
                continue
            counts['links'] += 1
            where = '%s:%d' % (os.path.relpath(path, SOURCE), number)
            file_part, _, anchor = target.partition('#')
            resolved = os.path.normpath(os.path.join(os.path.dirname(path), file_part)) if file_part else path
            if not os.path.exists(resolved):
                fail(where, 'link to %s: no such file' % target)
                continue
            if anchor:
                if not resolved.endswith('.md'):
                    fail(where, 'link to %s: an anchor into a file that is not Markdown' % target)
                elif anchor not in anchors(resolved, slug_github) or anchor not in anchors(resolved, slug_mkdocs):
                    fail(where, 'link to %s: no heading with the anchor #%s (GitHub and mkdocs)' % (target, anchor))


# ---- loading environments and scripts ----
def run(args, cwd, timeout=60):
    try:
        return subprocess.run(args, cwd=cwd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return subprocess.CompletedProcess(args, 124, '', 'timed out after %d s' % timeout)


def environments(block):
    text = '\n'.join(block.lines)
    try:
        values = [json.loads(text)]
    except ValueError:
        try:
            values = [json.loads(line) for line in block.lines if line.strip()]
        except ValueError:
            return []  # a fragment ("...", one key, an effect)
    return [v for v in values if isinstance(v, dict) and 'effects' in v]


def probe_loads(env_path, cwd):
    """hapscene probe at one point: the cheapest command that loads a whole environment."""
    result = run([BINARY, 'probe', env_path, '--x', '0:0:1mm'], cwd)
    if result.returncode != 0 and '--y' in result.stderr:  # a 2-DOF scene takes a grid
        result = run([BINARY, 'probe', env_path, '--x', '-15mm:-15mm:1mm', '--y', '130mm:130mm:1mm'], cwd)
    return result


def check_json(path, block, folder, written=None):
    """written: the block as a file of its own (<!-- file: -->), loaded where it is."""
    for n, env in enumerate(environments(block)):
        counts['json'] += 1
        name = written or os.path.join(folder, 'env', 'block%d_%d.json' % (block.start, n))
        if not written:
            with open(name, 'w') as out:
                json.dump(env, out)
        result = probe_loads(name, folder)
        if result.returncode != 0:
            fail('%s:%d' % (os.path.relpath(path, SOURCE), block.start), 'environment does not load: ' + result.stderr.strip())


def check_lua(path, block, folder, script=None):
    text = '\n'.join(block.lines)
    if 'function force' not in text or re.search(r'^\s*\.\.\.\s*$|abridged', text, re.M):
        return
    counts['lua'] += 1
    if script is None:
        script = os.path.join(folder, 'env', 'block%d.lua' % block.start)
        with open(script, 'w') as out:
            out.write(text + '\n')
    result = probe_loads(script, folder)
    if result.returncode != 0 and '2-D' in result.stderr:
        planar = script[:-4] + '_planar.json'
        with open(planar, 'w') as out:
            json.dump({'device': 'haplink', 'effects': [{'type': 'script', 'file': os.path.basename(script)}]}, out)
        result = probe_loads(planar, folder)
    if result.returncode != 0:
        fail('%s:%d' % (os.path.relpath(path, SOURCE), block.start), 'script does not load: ' + result.stderr.strip())


# ---- command lines ----
def commands(block):
    """(command, expected output lines or None) for each command line of a sh or console block."""
    console = block.lang == 'console' or any(l.startswith('$ ') for l in block.lines)
    out, lines = [], list(block.lines)
    while lines:
        line = lines.pop(0)
        if console and not line.startswith('$ '):
            if out and out[-1][1] is not None:
                out[-1][1].append(line)
            continue
        line = line[2:] if console else line
        while line.rstrip().endswith('\\') and lines:
            line = line.rstrip()[:-1] + ' ' + lines.pop(0).strip()
        if line.strip() and not line.lstrip().startswith('#'):
            out.append((line, [] if console else None))
    return out


def hapscene_calls(command):
    """The argument lists of the hapscene invocations in one shell line."""
    lexer = shlex.shlex(command, posix=True, punctuation_chars=';&|')
    lexer.whitespace_split, lexer.commenters = True, '#'
    try:
        tokens = list(lexer)
    except ValueError:
        return []
    calls, current = [], []
    for token in tokens + [';']:
        if token in (';', '&&', '||', '|', '&'):
            words = [t for t in current if not re.match(r'^[A-Z_]+=', t)]  # VAR=value prefixes
            if words and os.path.basename(words[0]) == 'hapscene':
                calls.append(words[1:])
            current = []
        else:
            current.append(token)
    return calls


def check_parse(path, number, args):
    counts['parsed'] += 1
    where = '%s:%d' % (os.path.relpath(path, SOURCE), number)
    self_describing = not args or args[0] in ('help', 'version', '--version', '-V', 'completion', 'man', '--help', '-h')
    if self_describing or '--help' in args or '-h' in args:
        result = run([BINARY] + args, SOURCE)
        if result.returncode != 0:
            fail(where, 'hapscene %s: exit %d: %s' % (' '.join(args), result.returncode, result.stderr.strip()))
        return
    given = list(args)
    given.insert(given.index('--') if '--' in given else len(given), SENTINEL)
    result = run([BINARY] + given, SOURCE)
    if result.returncode != 2 or 'unknown option ' + SENTINEL not in result.stderr:
        fail(where, 'hapscene %s: not parsed: %s' % (' '.join(args), (result.stderr or result.stdout).strip()[:300]))


def compare(expected, actual):
    """Line by line; an expected line `...` stands for any number of lines."""
    expected = [l.rstrip() for l in expected]
    while expected and not expected[-1]:
        expected.pop()
    actual = [l.rstrip() for l in actual.rstrip('\n').split('\n')] if actual.strip() else []

    def match(e, a):
        if e == len(expected):
            return a == len(actual)
        if expected[e] == '...':
            return any(match(e + 1, k) for k in range(a, len(actual) + 1))
        return a < len(actual) and expected[e] == actual[a] and match(e + 1, a + 1)
    return match(0, 0)


def run_page(path, blocks, folder):
    for block in blocks:
        where = '%s:%d' % (os.path.relpath(path, SOURCE), block.start)
        if 'no-test' in block.directives:
            continue
        if 'file' in block.directives:
            name = os.path.join(folder, block.directives['file'])
            with open(name, 'w') as out:
                out.write('\n'.join(block.lines) + '\n')
            if block.lang == 'json':
                check_json(path, block, folder, name)
            elif block.lang == 'lua':
                check_lua(path, block, folder, name)
            continue
        if block.lang not in ('sh', 'console'):
            continue
        exit_code = int(block.directives.get('exit', '0'))
        for command, expected in commands(block):
            counts['run'] += 1
            result = run(['bash', '-c', command], folder)
            if result.returncode != exit_code:
                fail(where, '`%s` exited %d, expected %d: %s' % (command, result.returncode, exit_code,
                                                                 (result.stderr or result.stdout).strip()[:500]))
            elif expected is not None and not compare(expected, result.stdout + result.stderr):
                fail(where, '`%s` printed\n%s\nthe page shows\n%s' % (command, result.stdout + result.stderr,
                                                                       '\n'.join(expected)))


def check_code_references():
    """Paths of pages named in the sources (comments, messages, schemas) exist, and no source
    points into a README section: those sections are pages under docs/ now."""
    for top in ('engine', 'schemas', 'python', 'tests', 'scripts', 'firmware', 'protocol', '.ci', 'docs'):
        for folder, _, names in os.walk(os.path.join(SOURCE, top)):
            for name in names:
                path = os.path.join(folder, name)
                if os.path.abspath(path) == os.path.abspath(__file__):
                    continue
                if name.endswith(('.md', '.csv', '.svg', '.elf', '.hex')) or 'corpus' in path or 'golden' in path:
                    continue
                try:
                    text = open(path, encoding='utf-8').read()
                except (UnicodeDecodeError, OSError):
                    continue
                where = os.path.relpath(path, SOURCE)
                for page in set(re.findall(r'\bdocs/[\w/.-]+\.md', text)):
                    counts['links'] += 1
                    if not os.path.exists(os.path.join(SOURCE, page)):
                        fail(where, 'names %s: no such page' % page)
                if re.search(r'README(\.md)?(\'s)?,? \(?\\?"|README \(|README, [A-Z]', text):
                    fail(where, 'points into a README section; name the page under docs/ instead')


def first_environment(path):
    text = open(path, encoding='utf-8').read()
    m = re.search(r'<!-- first-environment: begin.*?-->\n(.*?)<!-- first-environment: end -->', text, re.S)
    return re.sub(r'\]\([^)]*\)', '](...)', m.group(1)) if m else None


def scratch_folder(root, name):
    folder = os.path.join(root, name)
    os.makedirs(os.path.join(folder, 'build'))
    os.makedirs(os.path.join(folder, 'env'))
    for linked in ('environments', 'scripts', 'schemas'):
        os.symlink(os.path.join(SOURCE, linked), os.path.join(folder, linked))
    os.symlink(BINARY, os.path.join(folder, 'build', 'hapscene'))
    return folder


def main():
    root = tempfile.mkdtemp(prefix='hapscene-docs-')
    try:
        os.makedirs(os.path.join(root, 'bin'))
        os.symlink(BINARY, os.path.join(root, 'bin', 'hapscene'))
        os.environ['PATH'] = os.path.join(root, 'bin') + os.pathsep + os.environ['PATH']
        loads = scratch_folder(root, 'loads')
        for page_number, path in enumerate(markdown_files()):
            check_links(path)
            prose, blocks = parse(path)
            for block in blocks:
                if block.lang == 'json' and 'no-test' not in block.directives and 'file' not in block.directives:
                    check_json(path, block, loads)
                elif block.lang == 'lua' and 'no-test' not in block.directives and 'file' not in block.directives:
                    check_lua(path, block, loads)
                elif block.lang in ('sh', 'console', 'bash'):
                    for command, _ in commands(block):
                        for args in hapscene_calls(command):
                            check_parse(path, block.start, args)
            relative = os.path.relpath(path, SOURCE)
            if relative.startswith('docs/tutorials/'):
                run_page(path, blocks, scratch_folder(root, 'page%d' % page_number))
            elif relative == 'README.md':
                text = open(path, encoding='utf-8').read()
                begin = text.index('<!-- first-environment: begin')
                end = text.index('<!-- first-environment: end')
                first_line, last_line = text[:begin].count('\n'), text[:end].count('\n')
                run_page(path, [b for b in blocks if first_line < b.start < last_line + 1],
                         scratch_folder(root, 'page%d' % page_number))
        check_code_references()
        # The site's navigation (mkdocs.yml) lists every page, and only pages that exist.
        nav = set(re.findall(r':\s*([\w/.-]+\.md)\s*$', open(os.path.join(SOURCE, 'mkdocs.yml')).read(), re.M))
        pages = {os.path.relpath(p, os.path.join(SOURCE, 'docs')) for p in markdown_files() if '/docs/' in p}
        for page in sorted(pages - nav):
            fail('mkdocs.yml', 'the nav does not list docs/' + page)
        for page in sorted(nav - pages):
            fail('mkdocs.yml', 'the nav lists docs/%s, which does not exist' % page)
        readme, index = (first_environment(os.path.join(SOURCE, p)) for p in ('README.md', 'docs/index.md'))
        if readme is None or readme != index:
            fail('docs/index.md', 'its "first environment" differs from README.md\'s (or a marker is missing)')
    finally:
        shutil.rmtree(root, ignore_errors=True)
    print('docs: %(links)d links, %(json)d environments and %(lua)d scripts loaded, %(parsed)d command lines '
          'parsed, %(run)d commands run' % counts)
    for f in failures:
        print('FAIL ' + f)
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
