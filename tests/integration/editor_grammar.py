#!/usr/bin/env python3
"""The TextMate grammar of editors/vscode highlights the language as cbtlc reads it.

usage: editor_grammar.py REPO_ROOT

- the grammar and the extension manifest are valid JSON and point at each other;
- every keyword of grammar/Cbtl.g4 is highlighted as a keyword (a keyword added to the language and not to the
  highlighter fails here);
- every regex compiles, and a small TextMate-style tokenizer (earliest match wins, then pattern order; comments
  and strings as begin/end regions) run over every domain and standard-library file scopes every keyword token
  as a keyword or constant, never a comment's or a string's text as code, and every comment as a comment.
"""

import glob
import json
import os
import re
import sys

root = sys.argv[1]
failures = []
grammar_path = os.path.join(root, "editors/vscode/syntaxes/cbtl.tmLanguage.json")
grammar = json.load(open(grammar_path))
package = json.load(open(os.path.join(root, "editors/vscode/package.json")))
if grammar.get("scopeName") != "source.cbtl":
    failures.append("scopeName is not source.cbtl")
declared = package["contributes"]["grammars"][0]
if os.path.normpath(os.path.join(root, "editors/vscode", declared["path"])) != os.path.normpath(grammar_path):
    failures.append("package.json does not point at the grammar")
if ".cbtl" not in package["contributes"]["languages"][0]["extensions"]:
    failures.append("package.json does not claim .cbtl files")

lexer = open(os.path.join(root, "grammar/Cbtl.g4")).read()
keywords = set(re.findall(r"^[A-Z_]+\s*:\s*'([a-zA-Z]+)'\s*;", lexer, re.M))
if len(keywords) < 40:
    failures.append("found only %d keywords in Cbtl.g4" % len(keywords))


def flatten(patterns, repo):
    """The top-level patterns with includes resolved, in order."""
    out = []
    for p in patterns:
        if "include" in p:
            target = repo[p["include"][1:]]
            out += flatten(target["patterns"], repo) if "patterns" in target and "match" not in target \
                and "begin" not in target else [target]
        else:
            out.append(p)
    return out


rules = flatten(grammar["patterns"], grammar["repository"])
compiled = []
for r in rules:
    try:
        if "match" in r:
            compiled.append(("match", re.compile(r["match"], re.M), r))
        else:
            compiled.append(("region", re.compile(r["begin"], re.M), r, re.compile(r["end"], re.M)))
    except re.error as e:
        failures.append("a regex does not compile: %s (%s)" % (r, e))

keyword_rules = [r for r in rules if r.get("name", "").startswith(("keyword", "constant.language"))]
for kw in sorted(keywords):
    if not any(re.fullmatch(r["match"], kw) for r in keyword_rules if "match" in r):
        failures.append("the keyword '%s' is not highlighted as a keyword" % kw)


def scopes_of(rule, m):
    """(start, end, scope) for each scoped part of a match."""
    out = []
    if "name" in rule:
        out.append((m.start(), m.end(), rule["name"]))
    for index, cap in rule.get("captures", {}).items():
        if m.group(int(index)) is not None:
            out.append((m.start(int(index)), m.end(int(index)), cap["name"]))
    return out


def tokenize(text):
    """Scoped spans of a whole file, TextMate style: at each position the earliest match, ties to the first rule."""
    spans, pos = [], 0
    while pos < len(text):
        best = None
        for entry in compiled:
            m = entry[1].search(text, pos)
            if m and m.end() > m.start() and (best is None or m.start() < best[0].start()):
                best = (m, entry)
        if best is None:
            break
        m, entry = best
        if entry[0] == "match":
            spans += scopes_of(entry[2], m)
            pos = m.end()
        else:
            end = entry[3].search(text, m.end())
            stop = end.end() if end else len(text)
            spans.append((m.start(), stop, entry[2]["name"]))
            pos = stop
    return spans


files = sorted(glob.glob(os.path.join(root, "domains/*/*.cbtl")) + glob.glob(os.path.join(root, "stdlib/std/*.cbtl")))
token = re.compile(r'//[^\n]*|/\*.*?\*/|"(?:[^"\\\n]|\\.)*"|[A-Za-z_][A-Za-z_0-9]*', re.S)
for path in files:
    text = open(path).read()
    spans = tokenize(text)
    covering = {}
    for start, end, scope in spans:
        for i in (start, end - 1):
            covering.setdefault(i, []).append((start, end, scope))

    def scope_at(offset):
        best = [s for s in spans if s[0] <= offset < s[1]]
        return min(best, key=lambda s: s[1] - s[0])[2] if best else None

    for t in token.finditer(text):
        word = t.group(0)
        scope = scope_at(t.start())
        if word.startswith("//") or word.startswith("/*"):
            if not scope or not scope.startswith("comment"):
                failures.append("%s:%d: a comment is scoped %s" % (path, text.count("\n", 0, t.start()) + 1, scope))
        elif word.startswith('"'):
            if not scope or not scope.startswith(("string", "constant.character", "variable.other.capture")):
                failures.append("%s:%d: a string is scoped %s" % (path, text.count("\n", 0, t.start()) + 1, scope))
        elif word in keywords:
            if not scope or not scope.startswith(("keyword", "constant.language")):
                failures.append("%s:%d: keyword '%s' is scoped %s" % (path, text.count("\n", 0, t.start()) + 1,
                                                                       word, scope))
for f in failures[:30]:
    print("FAIL:", f)
print("editor grammar: %d keywords, %d files tokenized, %d failure(s)" % (len(keywords), len(files), len(failures)))
sys.exit(1 if failures else 0)
