# tests/build/test_layout.sh: the tree keeps the shape README "Layout" describes: files depend one way (no #include
# cycle), the core has no GL, the library reads none of the platform's configuration, the program uses only the
# public header of the library, every source file says on its first line what it is for, and none grows past 500
# lines outside tests and generated code.
. tests/lib.sh

# All #include "x.h" edges between our files, as "from to" lines of paths (resolved in the including file's folder,
# then in the include folders the build uses).
DIRS="include src/core src/gpu app platform/display platform/input platform/sim tools/pathtrace tools/mie tools/slab tools/sweep"
edges=$(for f in $(find include src app platform tools -name '*.[ch]' | sort); do
  sed -n 's/^#include "\([^"]*\)".*/\1/p' "$f" | while read -r h; do
    for d in "$(dirname "$f")" $DIRS; do
      if [ -f "$d/$h" ]; then echo "$f $d/$h" | sed 's|/\./|/|g'; break; fi
    done
  done
done)

# A cycle in the graph of header-to-implementation modules: a.c includes b.h whose b.c includes a.h. Modules are
# files without their extension; a module never counts as depending on itself.
mods=$(echo "$edges" | awk '{a=$1; b=$2; sub(/\.[ch]$/, "", a); sub(/\.[ch]$/, "", b); if (a != b) print a, b}' | sort -u)
cycle=$(echo "$mods" | awk '
  { adj[$1] = adj[$1] " " $2; nodes[$1]; nodes[$2] }
  function dfs(n,   i, k, m, parts) {
    state[n] = 1; stack[++sp] = n
    k = split(adj[n], parts, " ")
    for (i = 1; i <= k; i++) {
      m = parts[i]
      if (state[m] == 1) { found = ""; for (j = 1; j <= sp; j++) if (stack[j] == m || found != "") found = found stack[j] " -> "; found = found m; return 1 }
      if (state[m] == 0 && dfs(m)) return 1
    }
    sp--; state[n] = 2; return 0
  }
  END { for (n in nodes) if (state[n] == 0 && dfs(n)) { print found; exit } }')
[ -z "$cycle" ] && t_ok "no include cycle between modules" || t_fail "no include cycle between modules" "$cycle"

# The core has no GL: no GL header, nothing of src/gpu.
bad=$(grep -l '#include <GLES\|#include <GL/\|#include <EGL' src/core/*.[ch] 2>/dev/null; echo "$edges" | awk '$1 ~ /^src\/core\// && $2 ~ /^src\/gpu\// {print $1}')
[ -z "$bad" ] && t_ok "src/core has no GL" || t_fail "src/core has no GL" "$(echo $bad)"

# The library reads none of the platform's configuration, and nothing of platform/ or app/.
bad=$(grep -l '#include "config.h"' src/*/*.[ch] 2>/dev/null; echo "$edges" | awk '$1 ~ /^src\// && $2 ~ /^(platform|app)\// {print $1}')
[ -z "$bad" ] && t_ok "the library reads no config.h, no platform/, no app/" || t_fail "the library reads no config.h" "$(echo $bad)"

# The library's objects get only the library's flags: nothing of the display or input back ends (build/flags/lib is
# what every library object is compiled with, rewritten by make when it changes).
if [ -f build/flags/lib ]; then
  if grep -q -- '-DCU_HAVE\|libdrm\|wayland\|gpiod\|-Iplatform' build/flags/lib; then
    t_fail "library objects get only the library's flags" "$(cat build/flags/lib)"
  else t_ok "library objects get only the library's flags"; fi
else t_fail "library objects get only the library's flags" "no build/flags/lib (run make first)"; fi

# The program sees only the public header of the library.
bad=$(echo "$edges" | awk '$1 ~ /^app\// && $2 ~ /^src\// {print $1 " -> " $2}')
[ -z "$bad" ] && t_ok "app/ includes only include/cumulo.h of the library" || t_fail "app/ uses private headers" "$(echo $bad)"

# The platform layer does not depend on the library.
bad=$(echo "$edges" | awk '$1 ~ /^platform\// && $2 ~ /^(src|app)\// {print $1 " -> " $2}')
[ -z "$bad" ] && t_ok "platform/ does not depend on the library or the program" || t_fail "platform/ depends on the library" "$(echo $bad)"

# Every source file's first line says what it is for: a comment of a few words at least.
bad=""
for f in $(find include src app platform tools tests -name '*.[ch]' | sort); do
  head -1 "$f" | grep -Eq '^/\* ([^ ]+ ){4,}' || bad="$bad $f"
done
[ -z "$bad" ] && t_ok "first line says what the file is for" || t_fail "first line says what the file is for" "$bad"

# No source file over 500 lines outside tests and generated code.
big=$(find include src app platform tools -name '*.[ch]' -exec wc -l {} + | awk '$2 != "total" && $1 > 500 {print $2 "(" $1 ")"}')
[ -z "$big" ] && t_ok "no source file over 500 lines" || t_fail "no source file over 500 lines" "$(echo $big)"
big=$(find shaders_gles -name '*.glsl' -o -name '*.frag' -o -name '*.vert' | xargs wc -l |
     awk '$2 != "total" && $1 > 500 {print $2 "(" $1 ")"}')
[ -z "$big" ] && t_ok "no shader over 500 lines" || t_fail "no shader over 500 lines" "$(echo $big)"
t_summary
