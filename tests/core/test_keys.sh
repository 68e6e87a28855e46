# tests/core/test_keys.sh: the key tables in README.md and docs/man/cumulo.scene.5 are what build/cumulo-keys prints
# from src/core/scene_keys.c (`make keys-docs` rewrites them), and the man page renders. Run from the repository root.
. tests/lib.sh
K=${CUMULO_KEYS:-${B:-build}/cumulo-keys}
T=${B:-build}/test-output/keys
mkdir -p "$T"

# $1 name, $2 file, $3 begin marker, $4 end marker, $5 tool option
same_block() {
  if ! "$K" "$5" >"$T/want" 2>"$T/err"; then t_fail "$1" "$K $5 failed: $(cat "$T/err")"; return; fi
  if ! sh tools/keys/splice.sh "$2" "$3" "$4" --extract >"$T/have" 2>"$T/err"; then
    t_fail "$1" "$(cat "$T/err")"; return
  fi
  if cmp -s "$T/want" "$T/have"; then t_ok "$1"
  else t_fail "$1" "differs from '$K $5' (run make keys-docs): $(diff "$T/have" "$T/want" | head -5 | tr '\n' ' ')"; fi
}
same_block "README.md key table is cumulo-keys --markdown" README.md '<!-- keys:begin -->' '<!-- keys:end -->' --markdown
same_block "cumulo.scene.5 key rows are cumulo-keys --man" docs/man/cumulo.scene.5 '.\" keys:begin' '.\" keys:end' --man

# Every key of the table is in both, once (a check on the tool's loops, independent of the splice): the Markdown has
# a header and a rule line before its rows.
md=$(( $("$K" --markdown | grep -c '^| ') - 2 ))
mn=$("$K" --man | grep -c '^\.B ')
if [ "$md" -gt 40 ] && [ "$md" = "$mn" ]; then t_ok "markdown and man list the same $md keys"
else t_fail "markdown and man list the same keys" "markdown $md, man $mn"; fi

t_expect "cumulo-keys without an option" 2 "usage: cumulo-keys" -- "$K"
case "$("$K" --help)" in *--markdown*--man*--version*) t_ok "cumulo-keys --help" ;; *) t_fail "cumulo-keys --help" "" ;; esac
case "$("$K" --version)" in "cumulo-keys "*) t_ok "cumulo-keys --version" ;; *) t_fail "cumulo-keys --version" "" ;; esac

if command -v groff >/dev/null 2>&1; then
  groff -ww -man -Tutf8 -z docs/man/cumulo.scene.5 >"$T/groff" 2>&1
  if [ $? -eq 0 ] && [ ! -s "$T/groff" ]; then t_ok "cumulo.scene.5 renders without groff warnings"
  else t_fail "cumulo.scene.5 renders without groff warnings" "$(head -5 "$T/groff" | tr '\n' ' ')"; fi
else t_skip "cumulo.scene.5 renders without groff warnings" "no groff"; fi
if command -v man >/dev/null 2>&1; then
  MANWIDTH=80 man -l docs/man/cumulo.scene.5 >"$T/man" 2>"$T/err"
  if [ $? -eq 0 ] && grep -q 'droplet_radius' "$T/man" && grep -q 'DIAGNOSTICS' "$T/man"; then t_ok "man -l renders cumulo.scene.5"
  else t_fail "man -l renders cumulo.scene.5" "$(head -3 "$T/err" | tr '\n' ' ')"; fi
else t_skip "man -l renders cumulo.scene.5" "no man"; fi

t_summary
