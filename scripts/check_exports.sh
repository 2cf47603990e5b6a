#!/usr/bin/env bash
# Checks that shared libraries export the public API only: every defined
# dynamic symbol is a name in namespace l2s (or its type information), and
# none belongs to a private namespace (l2s::detail, l2s::io::lzf, ::pcd, ::yaml)
# or an anonymous one. Prints the count per library.
#   scripts/check_exports.sh LIBRARY.so...
set -euo pipefail
status=0
for library in "$@"; do
  symbols=$(nm -DC --defined-only "$library" | cut -d' ' -f3- |
    sed -E 's/^(typeinfo name for|typeinfo for|vtable for|VTT for|non-virtual thunk to|virtual thunk to) //')
  count=$(printf '%s\n' "$symbols" | grep -c . || true)
  bad=$(printf '%s\n' "$symbols" | grep -v '^l2s::' || true)
  private=$(printf '%s\n' "$symbols" |
    grep -E '::detail::|^l2s::io::(lzf|pcd|yaml)::|anonymous namespace' || true)
  echo "$(basename "$library"): $count exported symbols"
  if [ -n "$bad$private" ]; then
    echo "  not public API:" >&2
    printf '%s\n%s\n' "$bad" "$private" | grep . | sort -u | head -40 | sed 's/^/    /' >&2
    status=1
  fi
done
exit $status
