#!/bin/sh
# check_exports.sh LIBRARY BOUND: the dynamic symbols LIBRARY defines are its
# public API and nothing else.  Each must be named in namespace superball
# (functions, data, and the vtables, typeinfo and thunks of its classes),
# none in a namespace `detail` or an anonymous namespace, none whose
# demangled name mentions a `::detail::` or anonymous-namespace name anywhere
# (a parameter or template argument: a public class's private member taking
# an internal type), and there must be fewer than BOUND of them.  Prints
# every offending symbol (demangled) and exits 1 when there is one; exits 0
# with a count otherwise.
set -eu
lib=$1
bound=$2
symbols=$(nm -D --defined-only --format=posix "$lib" | awk '{ print $1 }')
count=$(printf '%s\n' "$symbols" | grep -c . || true)
# The nested name a mangled symbol is in, as its source names separated by
# "::" (superball::numeric::CollisionSolver), or "" when it is not a nested
# name (std::, a global function, C symbols).
paths=$(printf '%s\n' "$symbols" | awk '
  {
    s = $1; path = ""
    if (s ~ /^_ZT[VIST]/) s = substr(s, 5)
    else if (s ~ /^_ZT[hv]/) { sub(/^_ZT[hv][^_]*_/, "", s); if (s ~ /^[^N]/) sub(/^[^_]*_/, "", s) }
    else if (s ~ /^_Z/) s = substr(s, 3)
    else s = ""
    if (s ~ /^N/) {
      s = substr(s, 2); sub(/^[rVKRO]+/, "", s)
      while (match(s, /^[0-9]+/)) {
        n = substr(s, 1, RLENGTH) + 0; id = substr(s, RLENGTH + 1, n); s = substr(s, RLENGTH + 1 + n)
        path = path (path == "" ? "" : "::") id
      }
    }
    print $1 " " path
  }')
bad=$(printf '%s\n' "$paths" | awk '
  $2 !~ /^superball(::|$)/ { print $1 " (not in namespace superball)"; next }
  $2 ~ /(^|::)detail(::|$)/ { print $1 " (in a namespace detail)"; next }
  $2 ~ /_GLOBAL__N/ { print $1 " (in an anonymous namespace)"; next }')
# Symbols in namespace superball whose whole demangled name (parameters and
# template arguments included) names an internal type.
named=$(printf '%s\n' "$paths" | awk '$2 ~ /^superball(::|$)/ && $2 !~ /(^|::)detail(::|$)/ && $2 !~ /_GLOBAL__N/ { print $1 }')
for n in $(printf '%s\n' "$named" | c++filt | grep -n -e '::detail::' -e '(anonymous namespace)' | cut -d: -f1); do
  bad="$bad
$(printf '%s\n' "$named" | sed -n "${n}p") (names a type of a namespace detail or an anonymous namespace)"
done
bad=$(printf '%s\n' "$bad" | grep . || true)
status=0
if [ -n "$bad" ]; then
  printf '%s\n' "$bad" | while read -r mangled why; do
    echo "$(basename "$lib"): exported: $(echo "$mangled" | c++filt) $why"
  done
  echo "$(basename "$lib"): $(printf '%s\n' "$bad" | grep -c .) of $count exported symbols are not its public API"
  status=1
fi
if [ "$count" -ge "$bound" ]; then
  echo "$(basename "$lib"): $count exported symbols, the bound is $bound"
  status=1
fi
[ "$status" -eq 0 ] && echo "$(basename "$lib"): $count exported symbols (bound $bound), all in namespace superball, none in detail or an anonymous namespace nor naming a type there"
exit $status
