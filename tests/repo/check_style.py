#!/usr/bin/python3
"""The code rules of docs/design.md section 10 that a machine can check (CTest entry repo.style, label unit):
 - no function in src/ is longer than 60 lines (its body, from the line after the opening brace to the line
   before the closing one);
 - at most 20 comparisons of a string with a literal (== "..." or != "...") in src/, each with a comment on its
   line or the line above that says why it is not a registry's row (the grammar of a file, a name the OS gives).

    /usr/bin/python3 tests/repo/check_style.py SOURCE_DIR
Exits 1 and lists what breaks a rule."""
import os
import re
import sys

MAX_LINES = 60
MAX_LITERALS = 20
LITERAL = re.compile(r'(==|!=)\s*"[^"]*"|"[^"]*"\s*(==|!=)')


def strip(text):
    """The text with comments, string and character literals blanked (newlines kept)."""
    out, i, n = [], 0, len(text)
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
        elif c == 'R' and text.startswith('R"', i):
            m = re.match(r'R"([^(]*)\(', text[i:])
            end = text.find(")" + m.group(1) + '"', i)
            j = end + len(m.group(1)) + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(c + " " * (j - i - 1) + c)
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def is_function(head):
    """Whether the text before a '{' (since the last ';', '{' or '}') is a function's signature."""
    head = head.strip()
    if not head or re.search(r"\b(class|struct|union|enum|namespace)\b[^()]*$", head):
        return False
    if re.search(r"\)\s*:\s*\w", head):  # a constructor's initialiser list
        return True
    head = re.sub(r"\s*->\s*[\w:<>,\s*&]+$", "", head)  # a trailing return type
    head = re.sub(r"(\b(const|noexcept|override|final|mutable)\b\s*)+$", "", head)
    return head.endswith(")") and not re.search(r"=\s*\[", head) and not re.search(r"\brequires\b", head)


def long_functions(path, text):
    code = strip(text)
    out, stack, head_start = [], [], 0
    line = 1
    for i, c in enumerate(code):
        if c == "\n":
            line += 1
        elif c == "{":
            in_function = any(kind == "function" for kind, _ in stack)
            kind = "function" if not in_function and is_function(code[head_start:i]) else "block"
            stack.append((kind, line))
            head_start = i + 1
        elif c == "}":
            kind, opened = stack.pop() if stack else ("block", line)
            if kind == "function" and line - opened - 1 > MAX_LINES:
                name = re.findall(r"([~\w:]+)\s*\(", code[:code.rfind("{", 0, i)].split("\n")[opened - 1] + " (")
                out.append(f"{path}:{opened}: a function of {line - opened - 1} lines (at most {MAX_LINES})")
            head_start = i + 1
        elif c == ";":
            head_start = i + 1
    return out


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else "."
    problems, literals = [], []
    for folder, _, files in os.walk(os.path.join(root, "src")):
        for name in sorted(files):
            if not name.endswith((".cpp", ".hpp")):
                continue
            path = os.path.join(folder, name)
            rel = os.path.relpath(path, root)
            text = open(path, encoding="utf-8").read()
            problems += long_functions(rel, text)
            lines = text.split("\n")
            for k, raw in enumerate(lines, 1):
                code = raw.split("//")[0]
                if LITERAL.search(code):
                    literals.append(f"{rel}:{k}")
                    if "//" not in raw and (k < 2 or not lines[k - 2].strip().startswith("//")):
                        problems.append(f"{rel}:{k}: a comparison with a literal without a comment saying why")
    if len(literals) > MAX_LITERALS:
        problems.append(f"{len(literals)} comparisons with a literal in src/ (at most {MAX_LITERALS}): "
                        + ", ".join(literals))
    for p in problems:
        print(p)
    print(f"check_style: {len(literals)} comparisons with a literal; {len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
