"""The steps of Scripts/make-handout.sh (docs/TEACHING.md).

  handout.py copy ROOT DEST   copy the NUL-separated paths read from
                              stdin (relative to ROOT) into DEST
  handout.py stub DEST WEEK   in DEST/Sources/Course, replace every
                              marked body of week WEEK or later by a
                              fatalError; print what was replaced and kept
  handout.py check ROOT WEEK  exit 1 unless every marker of ROOT is well
                              formed and week WEEK is marked
  handout.py list ROOT        print the marked bodies: week, method, file

A marked body is

    // BEGIN SOLUTION week N: TOPIC — WHAT TO WRITE
    //   more of WHAT TO WRITE (comment lines indented by three spaces)
    ...
    // END SOLUTION

inside a method; the lines between the description and END SOLUTION are
the model answer, and the whole body of the method.
"""
import os
import re
import shutil
import sys
import textwrap

BEGIN = re.compile(r'^(\s*)// BEGIN SOLUTION week (\d+): (.+?) — (.*)$')
MORE = re.compile(r'^\s*//   (.*)$')
END = re.compile(r'^\s*// END SOLUTION\s*$')
FUNC = re.compile(r'\b(?:func\s+(\w+)|(init)\s*[?!]?\s*\(|var\s+(\w+))')
TYPE = re.compile(
    r'^(?:(?:public|package|internal|fileprivate|private|final)\s+)*'
    r'(?:struct|class|enum|actor|extension)\s+(\w+)')


class MarkerError(Exception):
    pass


def copy(root, dest):
    paths = sys.stdin.buffer.read().split(b'\0')
    dest_real = os.path.realpath(dest)
    count = 0
    for raw in paths:
        if not raw:
            continue
        path = os.fsdecode(raw)
        source = os.path.join(root, path)
        if os.path.realpath(source).startswith(dest_real + os.sep):
            continue  # DEST itself inside the working tree
        if not os.path.lexists(source) or os.path.isdir(source):
            continue  # deleted in the working tree, or a submodule
        target = os.path.join(dest, path)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        if os.path.islink(source):
            os.symlink(os.readlink(source), target)
        else:
            shutil.copy2(source, target)
        count += 1
    print(f'make-handout: {count} files copied to {dest}')


def marked_bodies(path):
    """The marked bodies of one file: dicts of week, topic, what, method,
    the lines of BEGIN, of the first line of the answer and of END
    (0-based), and the indentation."""
    lines = open(path, encoding='utf-8').read().split('\n')
    found = []
    index = 0
    while index < len(lines):
        line = lines[index]
        if END.match(line):
            raise MarkerError(f'{path}:{index + 1}: END SOLUTION without BEGIN')
        begin = BEGIN.match(line)
        if not begin:
            if 'BEGIN SOLUTION' in line:
                raise MarkerError(
                    f'{path}:{index + 1}: expected "// BEGIN SOLUTION week N: '
                    'TOPIC — WHAT TO WRITE"')
            index += 1
            continue
        indent, week, topic, what = begin.groups()
        body = index + 1
        while body < len(lines) and MORE.match(lines[body]):
            what += ' ' + MORE.match(lines[body]).group(1).strip()
            body += 1
        end = body
        while end < len(lines) and not END.match(lines[end]):
            if 'BEGIN SOLUTION' in lines[end]:
                raise MarkerError(f'{path}:{end + 1}: BEGIN SOLUTION inside '
                                  f'the one of line {index + 1}')
            end += 1
        if end == len(lines):
            raise MarkerError(f'{path}:{index + 1}: BEGIN SOLUTION without END')
        found.append(dict(
            week=int(week), topic=topic.strip(), what=what.strip(),
            method=method_name(lines, index), begin=index, body=body,
            end=end, indent=indent))
        index = end + 1
    return lines, found


def method_name(lines, index):
    """Type.method of the declaration that holds line `index`."""
    method = type_name = None
    for line in reversed(lines[:index]):
        if method is None:
            match = FUNC.search(line)
            if match:
                method = next(group for group in match.groups() if group)
                continue
        match = TYPE.match(line)
        if match:
            type_name = match.group(1)
            break
    return '.'.join(name for name in (type_name, method) if name)


def swift_string(text):
    return text.replace('\\', '\\\\').replace('"', '\\"')


def fatal_error(marker):
    """The fatalError that stands for the marked body, wrapped to fit in 80
    columns as a sum of string literals."""
    message = (f"Week {marker['week']} ({marker['topic']}): write "
               f"{marker['method']}: {marker['what']} — see the lecture on "
               f"{marker['topic']}")
    indent = marker['indent']
    pieces = textwrap.wrap(swift_string(message), width=71 - len(indent),
                           break_long_words=False, break_on_hyphens=False)
    pieces = [piece + ' ' for piece in pieces[:-1]] + pieces[-1:]
    out = [f'{indent}fatalError(', f'{indent}  "{pieces[0]}"']
    out += [f'{indent}    + "{piece}"' for piece in pieces[1:]]
    out[-1] += ')'
    return out


def course_files(root):
    folder = os.path.join(root, 'Sources', 'Course')
    for directory, _, names in sorted(os.walk(folder)):
        for name in sorted(names):
            if name.endswith('.swift'):
                yield os.path.join(directory, name)


def check(root, week):
    """Every marker of ROOT well formed, and week `week` marked."""
    weeks = {marker['week'] for path in course_files(root)
             for marker in marked_bodies(path)[1]}
    if week not in weeks:
        raise MarkerError(
            f'no method is marked for week {week} (weeks marked: '
            f'{", ".join(map(str, sorted(weeks))) or "none"})')


def stub(dest, week):
    check(dest, week)
    stubbed = kept = 0
    for path in course_files(dest):
        lines, markers = marked_bodies(path)
        relative = os.path.relpath(path, dest)
        for marker in reversed(markers):
            where = f"{relative}:{marker['begin'] + 1}"
            if marker['week'] < week:
                kept += 1
                print(f"  kept     week {marker['week']}: "
                      f"{marker['method']} ({where})")
                continue
            lines[marker['body']:marker['end']] = fatal_error(marker)
            stubbed += 1
            print(f"  to write week {marker['week']}: "
                  f"{marker['method']} ({where})")
        with open(path, 'w', encoding='utf-8') as file:
            file.write('\n'.join(lines))
    print(f'make-handout: week {week}: {stubbed} bodies to write, '
          f'{kept} of earlier weeks kept')


def list_markers(root):
    for path in course_files(root):
        _, markers = marked_bodies(path)
        for marker in markers:
            print(f"{marker['week']}\t{marker['method']}\t"
                  f"{os.path.relpath(path, root)}:{marker['begin'] + 1}")


def main(argv):
    try:
        if argv[1:2] == ['copy'] and len(argv) == 4:
            copy(argv[2], argv[3])
        elif argv[1:2] == ['check'] and len(argv) == 4:
            check(argv[2], int(argv[3]))
        elif argv[1:2] == ['stub'] and len(argv) == 4:
            stub(argv[2], int(argv[3]))
        elif argv[1:2] == ['list'] and len(argv) == 3:
            list_markers(argv[2])
        else:
            sys.exit(__doc__)
    except MarkerError as error:
        sys.exit(f'make-handout: {error}')


if __name__ == '__main__':
    main(sys.argv)
