#!/usr/bin/env python3
"""Fails if a library source file is longer than MAX_FILE_LINES or a function in it is longer
than MAX_FUNCTION_LINES: past those sizes a file holds more than one concept and a function
more than one step. Functions are found from braces (comments, strings and character literals
stripped): a block opened at namespace or class scope after a ')' is a function body, and
lambdas count towards the function around them.

Usage: check_sizes.py [--self-test] SOURCE_DIR
--self-test first checks that the check finds a long function, a long file and a long lambda
inside a function (and not a long class, namespace or initializer) in a made-up tree."""
import pathlib
import re
import sys

MAX_FILE_LINES = 600
MAX_FUNCTION_LINES = 100
LIBRARIES = ["util", "skeleton", "grain", "shader", "renderer", "fit", "cli"]


def strip(text):
    """The text with comments, strings and char literals blanked (newlines kept)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append("\n" * text.count("\n", i, j))
            i = j
        elif text.startswith('R"', i):
            m = re.match(r'R"([^(]*)\(', text[i:])
            end = text.find(")" + m.group(1) + '"', i) if m else -1
            j = n if end < 0 else end + len(m.group(1)) + 2
            out.append('""' + "\n" * text.count("\n", i, j))
            i = j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(c + c)
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def functions(text):
    """(name, first line, line count) of every function body."""
    code = strip(text)
    stack = []  # (kind, start line, head)
    head, line = "", 1
    found = []
    for c in code:
        if c == "\n":
            line += 1
            head += " "
        elif c == "{":
            inside = stack and stack[-1][0] in ("function", "block")
            h = head.strip()
            if inside:
                kind = "block"
            elif re.search(r"\bnamespace\b|^extern\b", h):
                kind = "namespace"
            elif re.search(r"\b(class|struct|union|enum)\b[^()]*$", h):
                kind = "class"
            elif ")" in h:
                kind = "function"
            else:
                kind = "block"
            stack.append((kind, line, h))
            head = ""
        elif c == "}":
            if stack:
                kind, start, h = stack.pop()
                if kind == "function":
                    name = re.sub(r"\s+", " ", h)[-80:]
                    found.append((name, start, line - start + 1))
            head = ""
        elif c == ";":
            head = ""
        else:
            head += c
    return found


def problems_in(root):
    problems = []
    for library in LIBRARIES:
        for path in sorted((root / library).rglob("*")):
            if path.suffix not in (".h", ".cpp"):
                continue
            text = path.read_text(encoding="utf-8")
            rel = path.relative_to(root)
            lines = text.count("\n")
            if lines > MAX_FILE_LINES:
                problems.append(f"{rel}: {lines} lines (at most {MAX_FILE_LINES})")
            for name, start, length in functions(text):
                if length > MAX_FUNCTION_LINES:
                    problems.append(f"{rel}:{start}: a function of {length} lines (at most "
                                    f"{MAX_FUNCTION_LINES}): {name}")
    return problems


def self_test():
    """The check on a made-up tree: what it must find and what it must leave."""
    import tempfile
    body = "".join(f"    x += {i};  // a {{ brace }}}} in a comment\n" for i in range(99))
    files = {
        "util/long_function.cpp": "namespace n {\nint f(int x) {\n" + body + "    return x;\n}\n}\n",
        "util/short_function.cpp": "int g(int x) {\n" + body[: len(body) // 2] + "    return x;\n}\n",
        "util/long_file.h": "// line\n" * 601,
        "util/class.h": "struct S {\n" + "    int a;\n" * 150 + "};\nconst int k[] = {\n"
                        + "    1,\n" * 150 + "};\n",
        "util/lambda.cpp": "void h() {\n    auto l = [](int x) {\n" + body + "        return x;\n"
                           "    };\n}\n",
        "util/strings.cpp": "const char* s = \"}}}}\";\nint m() {\n    return '{';\n}\n",
    }
    with tempfile.TemporaryDirectory() as tmp:
        for name, text in files.items():
            path = pathlib.Path(tmp) / name
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(text)
        found = problems_in(pathlib.Path(tmp))
    expected = ["util/lambda.cpp:1: a function of 104", "util/long_file.h: 601 lines",
                "util/long_function.cpp:2: a function of 102"]
    missing = [e for e in expected if not any(p.startswith(e) for p in found)]
    extra = [p for p in found if not any(p.startswith(e) for e in expected)]
    if missing or extra:
        print(f"self-test failed: missing {missing}, unexpected {extra}")
        return False
    return True


def main():
    args = sys.argv[1:]
    if args and args[0] == "--self-test":
        if not self_test():
            return 1
        args = args[1:]
    problems = problems_in(pathlib.Path(args[0]))
    if problems:
        print("too large; split by concept or by step:\n  " + "\n  ".join(problems))
        return 1
    print(f"sizes: every file <= {MAX_FILE_LINES} lines, every function <= "
          f"{MAX_FUNCTION_LINES} lines")
    return 0


if __name__ == "__main__":
    sys.exit(main())
