#!/usr/bin/env bash
# fmt_cli.sh CBTLC DOMAINS — `cbtlc fmt` as a user runs it: stdout by default, --write rewrites only what is not
# formatted (atomically, keeping permissions), --check changes nothing, stdin, and every refusal says why.
set -u
cbtlc=$(realpath "$1")
domains=$(realpath "$2")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
cd "$work" || exit 1

printf 'domain d;\nvar x:real in 0 ..1;\n   require small: x<0.5;\n' >messy.cbtl
printf 'domain d;\nvar x: real in 0 .. 1;\nrequire small: x < 0.5;\n' >expected.cbtl
cp "$domains/feeding/feeding.cbtl" tidy.cbtl
cp messy.cbtl messy.orig

# Default: the formatted file on stdout, the file itself untouched.
"$cbtlc" fmt messy.cbtl >out.cbtl || fail "fmt FILE exited $?"
cmp -s out.cbtl expected.cbtl || fail "fmt FILE printed: $(cat out.cbtl)"
cmp -s messy.cbtl messy.orig || fail "fmt FILE changed the file"
# Standard input, with and without `-`.
"$cbtlc" fmt <messy.cbtl >stdin1.cbtl && cmp -s stdin1.cbtl expected.cbtl || fail "fmt < FILE"
"$cbtlc" fmt - <messy.cbtl >stdin2.cbtl && cmp -s stdin2.cbtl expected.cbtl || fail "fmt - < FILE"

# --check: names the unformatted file, exit 1, changes nothing; a formatted file alone: exit 0, no output.
out=$("$cbtlc" fmt --check messy.cbtl tidy.cbtl)
code=$?
[ "$code" = 1 ] || fail "--check with an unformatted file exited $code"
[ "$out" = "messy.cbtl" ] || fail "--check printed '$out'"
cmp -s messy.cbtl messy.orig || fail "--check changed the file"
out=$("$cbtlc" fmt --check tidy.cbtl) || fail "--check of a formatted file exited $?"
[ -z "$out" ] || fail "--check of a formatted file printed '$out'"

# --write: rewrites the unformatted file, keeps its permissions, leaves a formatted file's inode alone, and leaves
# no temporary file behind.
chmod 640 messy.cbtl
tidy_inode=$(stat -c %i tidy.cbtl)
"$cbtlc" fmt --write messy.cbtl tidy.cbtl || fail "--write exited $?"
cmp -s messy.cbtl expected.cbtl || fail "--write wrote: $(cat messy.cbtl)"
[ "$(stat -c %a messy.cbtl)" = 640 ] || fail "--write changed the permissions to $(stat -c %a messy.cbtl)"
[ "$(stat -c %i tidy.cbtl)" = "$tidy_inode" ] || fail "--write replaced a file that was already formatted"
ls -A | grep -q 'cbtlc-fmt.tmp' && fail "--write left a temporary file: $(ls -A)"
"$cbtlc" fmt --write messy.cbtl && cmp -s messy.cbtl expected.cbtl || fail "a second --write changed the file"

# Refusals: a syntax error (file untouched, diagnostics with a location), a missing file, usage errors.
printf 'domain d;\nvar x : real in 0 .. 1\nrequire small: x < 0.5;\n' >broken.cbtl
cp broken.cbtl broken.orig
err=$("$cbtlc" fmt --write broken.cbtl 2>&1)
code=$?
[ "$code" = 1 ] || fail "a syntax error exited $code"
grep -q 'broken.cbtl:2:23: error\[E0102\]' <<<"$err" || fail "a syntax error said: $err"
grep -q 'not formatted' <<<"$err" || fail "a syntax error did not say the file was not formatted: $err"
cmp -s broken.cbtl broken.orig || fail "--write changed a file with a syntax error"
err=$("$cbtlc" fmt missing.cbtl 2>&1)
code=$?
[ "$code" = 1 ] && grep -q "cannot read file 'missing.cbtl'" <<<"$err" || fail "a missing file: exit $code: $err"
err=$("$cbtlc" fmt messy.cbtl tidy.cbtl 2>&1 >/dev/null)
code=$?
[ "$code" = 2 ] && grep -q -- "--write or --check" <<<"$err" || fail "two files to stdout: exit $code: $err"
err=$("$cbtlc" fmt --write --check messy.cbtl 2>&1)
code=$?
[ "$code" = 2 ] && grep -q "exclude each other" <<<"$err" || fail "--write --check: exit $code: $err"
err=$("$cbtlc" fmt --write <messy.cbtl 2>&1)
code=$?
[ "$code" = 2 ] && grep -q "needs files" <<<"$err" || fail "--write from stdin: exit $code: $err"
# A directory where a file should be is a file that cannot be read.
mkdir adir.cbtl
"$cbtlc" fmt --check adir.cbtl >/dev/null 2>&1
[ $? = 1 ] || fail "a directory was not refused"

[ "$failures" = 0 ] && echo "fmt_cli: all checks passed"
exit $((failures > 0))
