#!/bin/sh
# tools/keys/splice.sh FILE BEGIN END: replaces the lines between the marker lines BEGIN and END of FILE (each a whole
# line, kept) by standard input; `--extract` as a fourth argument prints those lines instead. Used by `make keys-docs`
# and tests/core/test_keys.sh, so both read the block the same way.
file=$1 begin=$2 end=$3
[ "$(grep -cxF -- "$begin" "$file")" = 1 ] && [ "$(grep -cxF -- "$end" "$file")" = 1 ] ||
  { echo "$file: needs one '$begin' line and one '$end' line" >&2; exit 1; }
if [ "$4" = --extract ]; then
  B=$begin E=$end awk '$0 == ENVIRON["E"] { on = 0 } on { print } $0 == ENVIRON["B"] { on = 1 }' "$file"
  exit
fi
tmp=$file.keys.tmp
cat >"$tmp.in" || exit 1
# the markers reach awk through the environment: -v would read the backslash of .\" as an escape
B=$begin E=$end G=$tmp.in awk '
  $0 == ENVIRON["B"] { print; while ((getline l < ENVIRON["G"]) > 0) print l; skip = 1; next }
  $0 == ENVIRON["E"] { skip = 0 }
  !skip { print }' "$file" >"$tmp" && mv -f "$tmp" "$file"
rc=$?
rm -f "$tmp.in"
exit $rc
