#!/usr/bin/env python3
"""Finds GoogleTest tests that pass whatever the code does: tests whose every
assertion sits behind a condition on the result (`if (result.found) {...}`,
`if (!found) continue;`). When nothing is found, such a test checks nothing.
A test that accepts "not found" must say so with an assertion of its own.

The rule: inside each TEST/TEST_F/TEST_P body, an assertion (EXPECT_*,
ASSERT_*) is guarded when it sits in the branch of an `if` (or its `else`)
whose condition names `found`, `success` or `ok`, or after such an `if` whose
statement leaves the block (`continue`, `return`, `break`). A test with
guarded assertions and no unguarded one fails the check. Assertions in
helper functions are not seen: a test that only calls helpers is not judged.

Usage: check_guarded_assertions.py FILE...   (exit 1 when a test is guarded)
       check_guarded_assertions.py --expect Suite.Name,... FILE...
              (exit 0 exactly when the guarded tests are those named: the
              check's own test, on a planted example)
"""
import re
import sys

RESULT_CONDITION = re.compile(r"\b(found|success|ok)\b")
ASSERTION = re.compile(r"\b(?:(?:EXPECT|ASSERT)_[A-Z_]+|FAIL|ADD_FAILURE|GTEST_SKIP)\s*\(")
TEST_START = re.compile(r"\b(TEST|TEST_F|TEST_P|TYPED_TEST|TYPED_TEST_P)\s*\(([^)]*)\)\s*\{")
LEAVES = re.compile(r"^\s*(continue|return|break)\b")
BRANCH_OR_ASSERTION = re.compile(r"\b(if|else)\b|" + ASSERTION.pattern)


def strip_comments_and_strings(text):
    """The source with comments, string and character literals blanked (same length)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(c + " " * (min(j, n - 1) - i - 1) + c)
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def matching(text, i, open_char, close_char):
    """Index just past the bracket that closes the one at text[i]."""
    depth = 0
    for j in range(i, len(text)):
        if text[j] == open_char:
            depth += 1
        elif text[j] == close_char:
            depth -= 1
            if depth == 0:
                return j + 1
    return len(text)


def statement_end(text, i):
    """Index just past the statement that starts at i (a block or up to its ';')."""
    while i < len(text) and text[i].isspace():
        i += 1
    if i < len(text) and text[i] == "{":
        return matching(text, i, "{", "}")
    depth = 0
    for j in range(i, len(text)):
        if text[j] in "({[":
            depth += 1
        elif text[j] in ")}]":
            depth -= 1
        elif text[j] == ";" and depth == 0:
            return j + 1
    return len(text)


def count_assertions(body, guarded):
    """(guarded, unguarded) assertion counts in `body`; `guarded`: all of it is."""
    counts = [0, 0]

    def add(part, part_guarded):
        g, u = count_assertions(part, part_guarded)
        counts[0] += g
        counts[1] += u

    i = 0
    while i < len(body):
        match = BRANCH_OR_ASSERTION.search(body, i)
        if not match:
            break
        word = match.group(1)
        if word is None:  # an assertion
            counts[0 if guarded else 1] += 1
            i = matching(body, match.end() - 1, "(", ")")
            continue
        if word == "if":
            open_paren = body.find("(", match.end())
            close = matching(body, open_paren, "(", ")")
            condition_guards = guarded or bool(RESULT_CONDITION.search(body[open_paren:close]))
            end = statement_end(body, close)
            branch = body[close:end]
            add(branch, condition_guards)
            i = end
            else_match = re.match(r"\s*else\b", body[i:])
            if else_match:
                else_end = statement_end(body, i + else_match.end())
                add(body[i + else_match.end():else_end], condition_guards)
                i = else_end
            # `if (!found) continue;`: the rest of the block runs only with a result.
            if condition_guards and not guarded and LEAVES.match(branch.strip(" \t\n{")):
                rest_end = block_end(body, i)
                add(body[i:rest_end], True)
                i = rest_end
            continue
        i = match.end()  # a stray `else` (its `if` handled it)
    return counts


def block_end(body, i):
    """Index of the `}` that closes the block enclosing position i (or the end)."""
    depth = 0
    for j in range(i, len(body)):
        if body[j] == "{":
            depth += 1
        elif body[j] == "}":
            if depth == 0:
                return j
            depth -= 1
    return len(body)


def guarded_tests(path):
    text = strip_comments_and_strings(open(path, encoding="utf-8").read())
    found = []
    for match in TEST_START.finditer(text):
        body_end = matching(text, match.end() - 1, "{", "}")
        guarded, unguarded = count_assertions(text[match.end():body_end - 1], False)
        if guarded and not unguarded:
            line = text.count("\n", 0, match.start()) + 1
            name = ".".join(part.strip() for part in match.group(2).split(","))
            found.append((line, name, guarded))
    return found


def main(args):
    expected = None
    if args[:1] == ["--expect"]:
        expected = set(args[1].split(","))
        args = args[2:]
    names = set()
    for path in args:
        for line, name, count in guarded_tests(path):
            print(f"{path}:{line}: {name}: all {count} assertions sit behind a condition on the result;"
                  " assert the outcome (ASSERT_TRUE(found) or ASSERT_FALSE(found)) first")
            names.add(name)
    if expected is None:
        return 1 if names else 0
    if names != expected:
        print(f"expected exactly {sorted(expected)} to be guarded, found {sorted(names)}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
